// libFuzzer target: the rig file reader as far as the file itself goes
// (geometry, body, sensors, simulation, uncertainties, effects blocks);
// the frame models it names are other files, fuzzed by fuzz_model_reader.
#include "fuzz_input.hpp"
#include "io/rig_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "rig.yaml",
                              [](const std::filesystem::path& file) { (void)rigflex::io::read_rig_spec(file); });
  return 0;
}
