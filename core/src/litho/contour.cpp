// Marching squares (contour.hpp). The crossings are the Python loop's that it replaced, in the
// same arithmetic; its saddle rule was the wrong way round (a centre on the first corner's side
// cut that corner off), which Contour.SaddleSplitsByTheMean found.
#include "linf/litho/contour.hpp"

#include <stdexcept>

namespace linf::litho {

std::vector<double> contour_segments(const std::vector<double>& values, int m, int lo, int hi, double level) {
  if (m < 1 || values.size() != std::size_t(m) * std::size_t(m))
    throw std::invalid_argument("contour: the image is not an m x m grid");
  if (lo < 0 || hi > m || lo > hi) throw std::invalid_argument("contour: the cells lie outside the grid");
  std::vector<double> out;
  for (int j = lo; j < hi - 1; ++j)
    for (int i = lo; i < hi - 1; ++i) {
      const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      double v[4];
      for (int k = 0; k < 4; ++k) v[k] = values[std::size_t(cj[k]) * std::size_t(m) + std::size_t(ci[k])];
      double pts[4][2];
      int found = 0;
      for (int a = 0; a < 4; ++a) {
        const int b = (a + 1) % 4;
        if ((v[a] >= level) != (v[b] >= level)) {
          const double t = (level - v[a]) / (v[b] - v[a]);
          pts[found][0] = ci[a] + t * (ci[b] - ci[a]);
          pts[found][1] = cj[a] + t * (cj[b] - cj[a]);
          ++found;
        }
      }
      auto add = [&](int p, int q) { out.insert(out.end(), {pts[p][0], pts[p][1], pts[q][0], pts[q][1]}); };
      if (found == 2) {
        add(0, 1);
      } else if (found == 4) {
        const double centre = (((v[0] + v[1]) + v[2]) + v[3]) / 4;
        // The centre on corner 0's side joins corners 0 and 2: the segments cut off 1 and 3.
        if ((centre >= level) == (v[0] >= level)) add(0, 1), add(2, 3);
        else add(0, 3), add(1, 2);
      }
    }
  return out;
}

}  // namespace linf::litho
