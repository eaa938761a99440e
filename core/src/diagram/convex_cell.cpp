#include "convex_cell.hpp"

#include <cmath>
#include <vector>

namespace linf::detail {

// The builder clips cells by the million, most often by a half-plane that holds the whole cell
// (a site far above another): the values are taken in one pass, and the cell is copied only
// when the line cuts it.
bool clip_in_place(Cell& c, const Affine& h) {
  const std::size_t n = c.v.size();
  if (n < 3) return false;
  // Values within rounding of zero count as on the line, so a line through a vertex never
  // produces a sliver. On the stack for the usual cells, of a few vertices.
  constexpr std::size_t kInline = 32;
  double inline_val[kInline];
  std::vector<double> heap_val;
  double* val = inline_val;
  if (n > kInline) heap_val.resize(n), val = heap_val.data();
  bool cuts = false, keeps = false;
  for (std::size_t i = 0; i < n; ++i) {
    double v = h.at(c.v[i].x, c.v[i].y);
    if (std::fabs(v) <= h.err(c.v[i].x, c.v[i].y) * 16) v = 0;
    val[i] = v;
    cuts |= v < 0;
    keeps |= v > 0;
  }
  if (!cuts) return true;
  if (!keeps) {
    c.v.clear();
    return false;
  }
  boost::container::small_vector<Vec2, kInline + 2> out;
  // Rounding can repeat a vertex: such repeats are dropped as they come.
  auto push = [&](const Vec2& p) {
    if (out.empty() || out.back().x != p.x || out.back().y != p.y) out.push_back(p);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i + 1 < n ? i + 1 : 0;
    const double vi = val[i], vj = val[j];
    if (vi >= 0) push(c.v[i]);
    if ((vi > 0 && vj < 0) || (vi < 0 && vj > 0)) {
      const double t = vi / (vi - vj);
      push({c.v[i].x + t * (c.v[j].x - c.v[i].x), c.v[i].y + t * (c.v[j].y - c.v[i].y)});
    }
  }
  if (out.size() > 1 && out.front().x == out.back().x && out.front().y == out.back().y) out.pop_back();
  c.v.assign(out.begin(), out.end());
  if (c.v.size() < 3 || area(c) <= 0) {
    c.v.clear();
    return false;
  }
  return true;
}

// From the first vertex: products of absolute coordinates near 2^30 round by more than a
// small cell's area, and its sign decides whether the cell is kept.
double area(const Cell& c) {
  double s = 0;
  const std::size_t n = c.v.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double px = c.v[i].x - c.v[0].x, py = c.v[i].y - c.v[0].y;
    const double qx = c.v[i + 1].x - c.v[0].x, qy = c.v[i + 1].y - c.v[0].y;
    s += px * qy - qx * py;
  }
  return 0.5 * s;
}

}  // namespace linf::detail
