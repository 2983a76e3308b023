// libFuzzer target: the measurement CSV reader of the data contract
// (shared/spec/rig-conventions.md), with its checks of every channel.
#include "fuzz_input.hpp"
#include "io/measurement_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "h1.csv", [](const std::filesystem::path& file) {
    (void)rigflex::io::read_measurement_file(file, rigflex::io::RodRule{});
  });
  return 0;
}
