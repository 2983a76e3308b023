// libFuzzer target: an effects file (what diagnose writes, what compare
// --effects reads) added to the bad-input catalogue's valid trifilar.
#include "fuzz_input.hpp"
#include "io/rig_reader.hpp"
#include "rig/rig_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rigflex::rig::RigModel base =
      rigflex::io::read_rig(rigflex::fuzz::source_dir() / "tests/bad-input/valid-rig.yaml");
  rigflex::fuzz::read_as_file(data, size, "effects.yaml", [](const std::filesystem::path& file) {
    rigflex::rig::RigModel model = base;
    rigflex::io::add_effects(model, file);
  });
  return 0;
}
