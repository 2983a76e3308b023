// libFuzzer target: the Abaqus / CalculiX deck reader (*INCLUDE resolved
// beside the input file, so a fuzzed include names a file that is not there).
#include "fuzz_input.hpp"
#include "io/model_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "deck.inp",
                              [](const std::filesystem::path& file) { (void)rigflex::io::read_model(file); });
  return 0;
}
