#include "cell.hpp"

#include <cmath>

namespace linf::detail {

Cell clip(const Cell& in, const Affine& h) {
  const std::size_t n = in.v.size();
  Cell out;
  if (n < 3) return out;
  boost::container::small_vector<double, 10> val(n);
  bool all_in = true, all_out = true;
  for (std::size_t i = 0; i < n; ++i) {
    double v = h.at(in.v[i].x, in.v[i].y);
    if (std::fabs(v) <= h.err(in.v[i].x, in.v[i].y) * 16) v = 0;
    val[i] = v;
    all_in &= v >= 0;
    all_out &= v <= 0;
  }
  if (all_in) return in;
  if (all_out) return out;
  out.v.reserve(n + 1);
  // Rounding can repeat a vertex: such repeats are dropped as they come.
  auto push = [&](const Vec2& p) {
    if (out.v.empty() || out.v.back().x != p.x || out.v.back().y != p.y) out.v.push_back(p);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double vi = val[i], vj = val[j];
    if (vi >= 0) push(in.v[i]);
    if ((vi > 0 && vj < 0) || (vi < 0 && vj > 0)) {
      const double t = vi / (vi - vj);
      push({in.v[i].x + t * (in.v[j].x - in.v[i].x), in.v[i].y + t * (in.v[j].y - in.v[i].y)});
    }
  }
  if (out.v.size() > 1 && out.v.front().x == out.v.back().x && out.v.front().y == out.v.back().y) out.v.pop_back();
  if (out.v.size() < 3 || area(out) <= 0) return Cell{};
  return out;
}

bool clip_in_place(Cell& c, const Affine& h) {
  for (const Vec2& p : c.v)
    if (h.at(p.x, p.y) < -16 * h.err(p.x, p.y)) {
      c = clip(c, h);
      return !c.empty();
    }
  return !c.empty();
}

double area(const Cell& c) {
  double s = 0;
  for (std::size_t i = 0, n = c.v.size(); i < n; ++i) {
    const Vec2& p = c.v[i];
    const Vec2& q = c.v[(i + 1) % n];
    s += p.x * q.y - q.x * p.y;
  }
  return 0.5 * s;
}

}  // namespace linf::detail
