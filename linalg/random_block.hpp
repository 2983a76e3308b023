#pragma once
// Deterministic pseudo-random start vectors: the same seed gives bitwise the
// same numbers with any standard library (std::uniform_real_distribution is
// implementation-defined, so the bits of mt19937_64 are mapped by hand).
#include <Eigen/Core>
#include <cstdint>
#include <random>

namespace rigflex::linalg {

class RandomBlocks {
 public:
  explicit RandomBlocks(std::uint64_t seed) : engine_(seed) {}

  // Entries uniform in [-1, 1).
  Eigen::MatrixXd next(Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd x(rows, cols);
    fill(x);
    return x;
  }

  // Same numbers as next(x.rows(), x.cols()), written into x.
  void fill(Eigen::Ref<Eigen::MatrixXd> x) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      for (Eigen::Index i = 0; i < x.rows(); ++i) {
        x(i, j) = static_cast<double>(engine_() >> 11) * 0x1.0p-52 - 1.0;
      }
    }
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace rigflex::linalg
