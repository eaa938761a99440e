// The aerial image of a window: I(x) = sum_i w_i |E_i(x)|^2, E_i the field of kernel i, whose
// spectrum is K_i(k) c(k) (c the mask's coefficients). The fields' spectra are computed once;
// the image is then read on a grid (FFTW) or at any point (the band-limited sum), from the
// same spectra, so the two agree to rounding.
#pragma once
#include <complex>
#include <memory>
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

// The image on an m x m grid (AerialImage::grid's layout, period `period` nm) blurred in place by
// a Gaussian of standard deviation `sigma` nm in both directions (a resist's diffusion), by
// its exact transform on the grid's frequencies. sigma = 0 changes nothing.
void blur_grid(std::vector<double>& values, int m, double period, double sigma);

// The kernels laid out for line profiles, made once a model: for a line along x and one along
// y, each kernel's values with, for each frequency along the line, the frequencies across it
// contiguous, real and imaginary parts apart, and for each frequency along the line the span
// across it where some kernel is not zero (the pupil's disc: a fifth of the square is zero).
// The loops over them then run over plain arrays of doubles.
class LineKernels {
 public:
  explicit LineKernels(const Kernels& kernels);
  const Kernels& kernels() const { return *kernels_; }

 private:
  friend class LineProfile;
  const Kernels* kernels_;
  std::size_t n_;
  // [axis][(i * n + a) * n + b]: kernel i at frequency a - h along the line, b - h across it;
  // axis 0 a line along x, 1 along y.
  std::vector<double> re_[2], im_[2];
  std::vector<std::size_t> lo_[2], hi_[2];  // [axis][a]: the nonzero b are in [lo, hi)
};

// A line to read: its window's mask, a point p on it (nm from the window's corner) and its
// direction d.
struct Probe {
  const MaskSpectrum* mask;
  double px, py, dx, dy;
};

// The image along the line p + t d (d a unit vector), cheap to evaluate many times. Along an
// axis (the measurement lines of a rectilinear layout) each kernel's field on the line is a 1-D
// sum over 2h + 1 frequencies, and the image, the weighted sum of their squared moduli, a real
// trigonometric polynomial of degree 2h in t whose coefficients are formed once: a point then
// costs 2h complex products whatever the number of kernels. Along another direction each point
// costs the full 2-D sum of the image.
class LineProfile {
 public:
  LineProfile(const AerialImage& image, double px, double py, double dx, double dy);
  // The same profile straight from the kernels and the mask, without the image's fields (what a
  // reading along an axis needs of a window: half the work of forming the fields first).
  LineProfile(const LineKernels& kernels, const MaskSpectrum& mask, double px, double py, double dx, double dy);
  // The profiles of several lines, each the same bits as the constructor above makes, with each
  // kernel's values read once for all of them. A model's kernels (euv: 24 x 47^2 complex values,
  // 850 kB a direction) outgrow the L2 cache and a few windows' masks do not, so one window at
  // a time would stream the kernels from memory for every line.
  static std::vector<LineProfile> batch(const LineKernels& kernels, const std::vector<Probe>& probes);
  // The same for several kernel sets of one period and size (a model's focus and defocused
  // kernels): [set][probe], each mask's layout made once for all of them.
  static std::vector<std::vector<LineProfile>> batch(const std::vector<const LineKernels*>& sets,
                                                     const std::vector<Probe>& probes);
  double at(double t) const;

  // The image blurred along the line by a Gaussian of standard deviation `sigma` nm (a resist's
  // diffusion, read across the features the line crosses). Along an axis each term g_d takes the
  // Gaussian's transform exp(-(sigma d omega)^2 / 2), exactly. Off an axis the image's spectrum,
  // exact from a grid of more than 4h samples a side (the image's frequencies reach 2h), takes it
  // for each frequency's component along the line, and points are summed from that spectrum.
  // sigma = 0 changes nothing; a negative or non-finite sigma is std::invalid_argument.
  void blur(double sigma);

 private:
  LineProfile(double px, double py) : px_(px), py_(py) {}
  void direction(double dx, double dy);
  // Folds each kernel's coefficients along the line (real and imaginary parts at [i * n + a],
  // frequency a - h) into the polynomial's: g_[d] = sum_i w_i sum_a c_i(a + d) conj(c_i(a)).
  void fold(const std::vector<double>& re, const std::vector<double>& im, const std::vector<double>& weights,
            std::size_t n);

  std::shared_ptr<const AerialImage> owned_;  // off an axis, built from kernels and mask
  const AerialImage* image_ = nullptr;
  double px_, py_, dx_ = 0, dy_ = 0;
  bool axis_ = false;
  double omega_ = 0;                    // 2 pi / P, signed by the direction along the axis
  std::vector<std::complex<double>> g_;  // along an axis: I(t) = g_0 + 2 Re sum_d g_d exp(i omega d t), d = 0..2h
  // Off an axis and blurred: the blurred image's spectrum, [(d + q) * (2q + 1) + e + q] for
  // frequencies |d|, |e| <= q = 2h (empty: read the image itself).
  std::vector<std::complex<double>> spectrum_;
  int q_ = 0;
};

}  // namespace linf::litho
