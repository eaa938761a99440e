// The aerial image of a window: I(x) = sum_i w_i |E_i(x)|^2, E_i the field of kernel i, whose
// spectrum is K_i(k) c(k) (c the mask's coefficients). The fields' spectra are computed once;
// the image is then read on a grid (FFTW) or at any point (the band-limited sum), from the
// same spectra, so the two agree to rounding.
#pragma once
#include <complex>
#include <vector>

#include "linf/litho/kernels.hpp"
#include "linf/litho/mask.hpp"

namespace linf::litho {

class AerialImage {
 public:
  // `mask` must have the kernels' period and at least their frequencies (half >= kernels.half()).
  AerialImage(const Kernels& kernels, const MaskSpectrum& mask);

  double period() const { return period_; }
  int half() const { return half_; }
  std::size_t kernel_count() const { return weights_.size(); }

  // The image at (x, y), nm from the window's lower-left corner (any real point; periodic).
  double at(double x, double y) const;

  // The image on an m x m grid of the period, pixel (i, j) at (i, j) * P / m from the window's
  // corner, returned row by row: value[j * m + i] (j along y). m >= 2 * half + 1; FFTW, the
  // kernels shared out to `threads` threads (0: one per core).
  std::vector<double> grid(int m, int threads = 0) const;

  // The fields' spectra (kernel i, frequency (kx, ky)): what a line profile reads.
  const std::complex<double>& field(std::size_t i, int kx, int ky) const {
    const std::size_t n = std::size_t(2 * half_ + 1);
    return fields_[i * n * n + std::size_t(kx + half_) * n + std::size_t(ky + half_)];
  }
  double weight(std::size_t i) const { return weights_[i]; }

 private:
  double period_;
  int half_;
  std::vector<double> weights_;
  std::vector<std::complex<double>> fields_;  // kernel by kernel, n x n each, kx major
};

// The image along the line p + t d (d a unit vector), cheap to evaluate many times: along an
// axis each field reduces once to a 1-D sum over 2 * half + 1 frequencies (the measurement
// lines of a rectilinear layout); along another direction each point costs the full 2-D sum.
class LineProfile {
 public:
  LineProfile(const AerialImage& image, double px, double py, double dx, double dy);
  double at(double t) const;

 private:
  const AerialImage& image_;
  double px_, py_, dx_, dy_;
  bool axis_ = false;
  std::vector<std::complex<double>> line_;  // per kernel, 2 * half + 1 coefficients along t
};

}  // namespace linf::litho
