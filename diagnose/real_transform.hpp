#pragma once
// One real FFT of length n and its inverse on owned buffers, the plans made
// and destroyed under diagnose's planner lock (fftw_planner.hpp). Internal
// to diagnose: it includes FFTW's header.
#include <fftw3.h>

#include <complex>
#include <cstddef>
#include <mutex>

#include "diagnose/fftw_planner.hpp"

namespace rigflex::diagnose {

class RealTransform {
 public:
  explicit RealTransform(int n)
      : n_(n), real_(fftw_alloc_real(static_cast<size_t>(n))), spectrum_(fftw_alloc_complex(bins())) {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    forward_ = fftw_plan_dft_r2c_1d(n, real_, spectrum_, FFTW_ESTIMATE);
    inverse_ = fftw_plan_dft_c2r_1d(n, spectrum_, real_, FFTW_ESTIMATE);
  }
  ~RealTransform() {
    {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(forward_);
      fftw_destroy_plan(inverse_);
    }
    fftw_free(spectrum_);
    fftw_free(real_);
  }
  RealTransform(const RealTransform&) = delete;
  RealTransform& operator=(const RealTransform&) = delete;

  int size() const { return n_; }
  size_t bins() const { return static_cast<size_t>(n_ / 2 + 1); }
  double* real() { return real_; }
  std::complex<double> bin(size_t k) const { return {spectrum_[k][0], spectrum_[k][1]}; }
  void set_bin(size_t k, std::complex<double> v) {
    spectrum_[k][0] = v.real();
    spectrum_[k][1] = v.imag();
  }
  void forward() { fftw_execute(forward_); }
  void inverse() { fftw_execute(inverse_); }  // unnormalized: n x the signal

 private:
  int n_;
  double* real_;
  fftw_complex* spectrum_;
  fftw_plan forward_, inverse_;
};

}  // namespace rigflex::diagnose
