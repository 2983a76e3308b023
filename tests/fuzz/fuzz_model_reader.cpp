// libFuzzer target: the FE model reader (rigflex modes/reduce input), every
// check of io/model_reader.cpp and the meshers it calls.
#include "fuzz_input.hpp"
#include "io/model_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "model.yaml",
                              [](const std::filesystem::path& file) { (void)rigflex::io::read_model(file); });
  return 0;
}
