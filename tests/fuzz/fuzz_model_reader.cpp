// libFuzzer target: the FE model reader (rigflex modes/reduce input), every
// check of io/model_reader.cpp and the meshers it calls.
#include <string_view>

#include "fuzz_input.hpp"
#include "io/model_reader.hpp"

namespace {

// A mesher asked for hundreds of divisions per edge is valid input (the
// readers refuse past 10000 per edge and 4e6 elements, tested in the
// bad-input catalogue) but takes minutes to mesh and check: a timeout, not
// a finding. Inputs with a count of three or more digits within a few
// characters after a count key are skipped.
bool asks_for_a_large_mesh(std::string_view text) {
  for (std::string_view key : {"divisions", "elements"}) {
    for (size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at + 1)) {
      const std::string_view after = text.substr(at + key.size(), 48);
      int digits = 0;
      for (char c : after) {
        digits = (c >= '0' && c <= '9') ? digits + 1 : 0;
        if (digits >= 3) return true;
      }
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (asks_for_a_large_mesh({reinterpret_cast<const char*>(data), size})) return 0;
  rigflex::fuzz::read_as_file(data, size, "model.yaml",
                              [](const std::filesystem::path& file) { (void)rigflex::io::read_model(file); });
  return 0;
}
