// The mask of a window: its polygons' exact Fourier coefficients at the kernels' frequencies.
//
// A window is a square period of side P nm (the kernels' period) whose lower-left corner is
// `origin` (in database units); the mask is 1 inside the polygons and 0 elsewhere, repeated
// with period P. Its coefficient at the integer frequency (kx, ky) is
//   c(kx, ky) = (1 / P^2) * integral over the polygons of exp(-2 pi i (kx x + ky y) / P),
// computed exactly, edge by edge (Green's theorem: each edge's trapezoid down to y = 0), for
// edges at any angle; no raster. c(0, 0) is the polygons' area fraction.
#pragma once
#include <complex>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::litho {

struct Window {
  Point origin;         // lower-left corner, database units
  double dbu_nm = 1.0;  // nm per database unit
};

class MaskSpectrum {
 public:
  // Coefficients for |kx|, |ky| <= half. The polygons (rings: outer first, holes after; any
  // orientation) must not overlap each other (a merged layer): overlaps would count twice.
  // Throws std::invalid_argument if a point lies outside the window [origin, origin + P].
  MaskSpectrum(const std::vector<Polygon>& polygons, const Window& window, double period_nm, int half);
  int half() const { return half_; }
  double period() const { return period_; }
  std::complex<double> at(int kx, int ky) const {
    const std::size_t k = std::size_t(kx + half_) * stride_ + std::size_t(ky + half_);
    return {re_[k], im_[k]};
  }

 private:
  int half_;
  double period_;
  // [(kx + half) * stride + ky + half], real and imaginary parts apart, each row padded with
  // zeros to a multiple of 8 (the products that fill them run 8 at a time).
  std::size_t stride_ = 0;
  std::vector<double> re_, im_;
};

}  // namespace linf::litho
