// libFuzzer target: the Gmsh mesh reader (MSH 4.1, ASCII and binary).
#include "fuzz_input.hpp"
#include "io/gmsh_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigflex::fuzz::read_as_file(data, size, "mesh.msh",
                              [](const std::filesystem::path& file) { (void)rigflex::io::read_gmsh(file); });
  return 0;
}
