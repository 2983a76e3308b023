// libFuzzer target: the Matrix Market reader of reduced-model imports, with
// and without the size the importer requires.
#include "fuzz_input.hpp"
#include "io/matrix_market.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "K.mtx", [](const std::filesystem::path& file) {
    (void)rigflex::io::read_matrix_market(file);
    (void)rigflex::io::read_matrix_market(file, rigflex::io::MatrixShape{3, 3, "a 3x3 test matrix"});
  });
  return 0;
}
