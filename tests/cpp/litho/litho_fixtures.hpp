// Shared by the litho tests: the kernels (shipped in models/, and the shared originals) and
// small masks.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "linf/geometry/site.hpp"
#include "linf/litho/kernels.hpp"
#include "linf/util/strided.hpp"

namespace litho_test {

// The iccad13 preset's kernels as the repository ships them (always present).
inline std::string shipped(const std::string& corner = "M1OPC") { return std::string(LINF_REPO) + "/models/iccad13/" + corner; }
// The shared originals (../shared/data): tests on them skip when they are missing.
inline std::string shared(const std::string& corner = "M1OPC") {
  return std::string(LINF_DATA) + "/openilt/kernels/" + corner;
}
inline bool exists(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}

inline const linf::litho::Kernels& focus() {
  static const linf::litho::Kernels k = linf::litho::read_kernels(shipped("M1OPC"));
  return k;
}

// A vector read in place, as the core reads a caller's column.
template <class T>
linf::Strided<T> column(const std::vector<T>& v) {
  return {reinterpret_cast<const char*>(v.data()), std::ptrdiff_t(sizeof(T)), v.size()};
}

inline linf::Polygon box(linf::Coord x0, linf::Coord y0, linf::Coord x1, linf::Coord y1) {
  return linf::Polygon{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}};
}

// The imaging model's symmetry lives in its TCC, T(f, g) = sum_i w_i K_i(f) conj(K_i(g)): the
// 8 transforms of the square (mirrors, quarter turns) map it onto itself up to the truncation
// to 24 kernels and the files' float32 rounding. This measures that defect; the image tests'
// symmetry tolerance is derived from it (|dI| <= ||dT|| sum |c|^2, test_image.cpp).
inline double tcc_symmetry_defect(const linf::litho::Kernels& k) {
  const int h = k.half(), n = k.size;
  auto T = [&](int fx, int fy, int gx, int gy) {
    std::complex<double> s = 0;
    for (std::size_t i = 0; i < k.count(); ++i) s += k.weights[i] * k.at(i, fx, fy) * std::conj(k.at(i, gx, gy));
    return s;
  };
  // The transforms as (x, y) -> (sx * (swap ? y : x), sy * (swap ? x : y)).
  double worst = 0;
  std::vector<std::complex<double>> t0(std::size_t(n) * n * n * n);
  for (int fx = -h; fx <= h; ++fx)
    for (int fy = -h; fy <= h; ++fy)
      for (int gx = -h; gx <= h; ++gx)
        for (int gy = -h; gy <= h; ++gy)
          t0[((std::size_t(fx + h) * n + std::size_t(fy + h)) * n + std::size_t(gx + h)) * n + std::size_t(gy + h)] =
              T(fx, fy, gx, gy);
  auto at = [&](int fx, int fy, int gx, int gy) {
    return t0[((std::size_t(fx + h) * n + std::size_t(fy + h)) * n + std::size_t(gx + h)) * n + std::size_t(gy + h)];
  };
  for (int swap = 0; swap < 2; ++swap)
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2) {
        double frob = 0;
        for (int fx = -h; fx <= h; ++fx)
          for (int fy = -h; fy <= h; ++fy)
            for (int gx = -h; gx <= h; ++gx)
              for (int gy = -h; gy <= h; ++gy) {
                const int Fx = sx * (swap ? fy : fx), Fy = sy * (swap ? fx : fy);
                const int Gx = sx * (swap ? gy : gx), Gy = sy * (swap ? gx : gy);
                frob += std::norm(at(Fx, Fy, Gx, Gy) - at(fx, fy, gx, gy));
              }
        worst = std::max(worst, std::sqrt(frob));
      }
  return worst;
}

}  // namespace litho_test
