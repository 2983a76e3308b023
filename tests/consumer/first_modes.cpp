// The lowest natural frequencies of a model file, through the installed
// rigflex package:  first_modes MODEL.yaml
#include <cstdio>

#include "io/model_reader.hpp"
#include "reduction/modal_analysis.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const auto file = rigflex::io::read_model(argv[1]);
  rigflex::linalg::EigenOptions options;
  options.count = 3;
  const auto modes = rigflex::reduction::run_modal_analysis(file.model, options);
  std::printf("mass %.6g kg\n", modes.mass.mass);
  for (int k = 0; k < modes.summary.frequencies_hz.size(); ++k) {
    std::printf("mode %d %.6g Hz\n", k + 1, modes.summary.frequencies_hz(k));
  }
  return modes.result.converged ? 0 : 1;
}
