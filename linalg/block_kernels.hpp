#pragma once
// Internal: the products on blocks of n-vectors that the eigen solver runs
// many times, and control of the BLAS threads.
//
// The BLAS is the optimized one that CHOLMOD brings into the process (the
// set-up selects OpenBLAS for it), found at run time so that rigflex links
// no BLAS of its own and runs unchanged (on Eigen's kernels, with no thread
// control) where none is found. Why bother: the dense products of a Lanczos
// basis (n x 40 times n x 4) run 2-3x faster in OpenBLAS's AVX2 kernels
// than in Eigen's, which are compiled for the baseline x86-64 instruction
// set; and OpenBLAS's threads, left on, slow down the many small kernels of
// a triangular solve (on a loaded machine by two orders of magnitude).
#include <dlfcn.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <limits>

namespace rigflex::linalg::detail {

// While alive, OpenBLAS runs on one thread. The setting is process-wide:
// BLAS calls on other threads meanwhile run serial too. Nests.
class SerialBlas {
 public:
  SerialBlas() {
    const Api& api = functions();
    if (api.get == nullptr || api.set == nullptr) return;
    saved_ = api.get();
    if (saved_ > 1) api.set(1);
  }
  ~SerialBlas() {
    if (saved_ > 1) functions().set(saved_);
  }
  SerialBlas(const SerialBlas&) = delete;
  SerialBlas& operator=(const SerialBlas&) = delete;

 private:
  struct Api {
    int (*get)() = nullptr;
    void (*set)(int) = nullptr;
  };
  static const Api& functions() {
    static const Api api = [] {
      Api a;
      a.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
      a.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
      return a;
    }();
    return api;
  }
  int saved_ = 0;
};

// C = alpha op(A) B + beta C, op(A) = A' if transpose_a; column-major
// blocks with unit inner stride.
inline void gemm(bool transpose_a, const Eigen::Ref<const Eigen::MatrixXd>& A,
                 const Eigen::Ref<const Eigen::MatrixXd>& B, double alpha, double beta,
                 Eigen::Ref<Eigen::MatrixXd> C) {
  using Dgemm = void (*)(const char*, const char*, const int*, const int*, const int*,
                         const double*, const double*, const int*, const double*, const int*,
                         const double*, double*, const int*);
  static const auto dgemm = reinterpret_cast<Dgemm>(dlsym(RTLD_DEFAULT, "dgemm_"));
  const Eigen::Index m = C.rows(), n = C.cols(), k = B.rows();
  const Eigen::Index largest = std::max({m, n, k, A.outerStride(), B.outerStride(), C.outerStride()});
  if (m == 0 || n == 0) return;
  // One column: Eigen's matrix-vector kernel is as fast (both are bound by
  // reading A), and OpenBLAS's dgemm is slower there.
  if (dgemm != nullptr && n > 1 && largest <= std::numeric_limits<int>::max() && k > 0) {
    const int im = static_cast<int>(m), in = static_cast<int>(n), ik = static_cast<int>(k);
    const int lda = static_cast<int>(A.outerStride()), ldb = static_cast<int>(B.outerStride()),
              ldc = static_cast<int>(C.outerStride());
    dgemm(transpose_a ? "T" : "N", "N", &im, &in, &ik, &alpha, A.data(), &lda, B.data(), &ldb,
          &beta, C.data(), &ldc);
    return;
  }
  if (beta == 0.0) {
    C.setZero();
  } else if (beta != 1.0) {
    C *= beta;
  }
  if (transpose_a) {
    C.noalias() += alpha * A.transpose() * B;
  } else {
    C.noalias() += alpha * A * B;
  }
}

// Columns kWidth of A X, kWidth a compile-time constant so that the sums
// stay in registers (twice as fast as a run-time width); see
// symmetric_times.
template <int kWidth>
void symmetric_times_columns(const Eigen::SparseMatrix<double>& A, const double* x,
                             Eigen::Index x_stride, double* ax, Eigen::Index ax_stride) {
  const auto* outer = A.outerIndexPtr();
  const auto* inner = A.innerIndexPtr();
  const auto* stored = A.innerNonZeroPtr();  // null when compressed
  const double* values = A.valuePtr();
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    std::array<double, kWidth> sum{};
    const Eigen::Index end = stored != nullptr ? outer[j] + stored[j] : outer[j + 1];
    for (Eigen::Index q = outer[j]; q < end; ++q) {
      const double v = values[q];
      const double* xq = x + inner[q];
      for (int c = 0; c < kWidth; ++c) sum[c] += v * xq[c * x_stride];
    }
    for (int c = 0; c < kWidth; ++c) ax[j + c * ax_stride] = sum[c];
  }
}

// AX = A X for a symmetric A stored by columns (both triangles), in one
// sweep over A per 8 columns of X: row j of A X is column j of A, as
// stored, times X. Eigen's kernels sweep A once per column of X, 2-3x
// slower from 4 columns up (1.4x for one column).
inline void symmetric_times(const Eigen::SparseMatrix<double>& A,
                            const Eigen::Ref<const Eigen::MatrixXd>& X,
                            Eigen::Ref<Eigen::MatrixXd> AX) {
  const Eigen::Index xs = X.outerStride(), as = AX.outerStride();
  for (Eigen::Index first = 0; first < X.cols();) {
    const Eigen::Index width = std::min<Eigen::Index>(8, X.cols() - first);
    const double* x = X.data() + first * xs;
    double* ax = AX.data() + first * as;
    switch (width) {
      case 1: symmetric_times_columns<1>(A, x, xs, ax, as); break;
      case 2: symmetric_times_columns<2>(A, x, xs, ax, as); break;
      case 3: symmetric_times_columns<3>(A, x, xs, ax, as); break;
      case 4: symmetric_times_columns<4>(A, x, xs, ax, as); break;
      case 5: symmetric_times_columns<5>(A, x, xs, ax, as); break;
      case 6: symmetric_times_columns<6>(A, x, xs, ax, as); break;
      case 7: symmetric_times_columns<7>(A, x, xs, ax, as); break;
      default: symmetric_times_columns<8>(A, x, xs, ax, as); break;
    }
    first += width;
  }
}

}  // namespace rigflex::linalg::detail
