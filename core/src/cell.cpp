#include "cell.hpp"

#include <cmath>

namespace linf::detail {

namespace {

// The values of h at the cell's vertices, those within rounding of zero made zero (on the
// line); false if every vertex is on the kept side, so that nothing needs clipping.
using Values = boost::container::small_vector<double, 10>;
bool values_at(const Cell& c, const Affine& h, Values& val) {
  const std::size_t n = c.v.size();
  val.resize(n);
  bool cuts = false;
  for (std::size_t i = 0; i < n; ++i) {
    double v = h.at(c.v[i].x, c.v[i].y);
    if (std::fabs(v) <= h.err(c.v[i].x, c.v[i].y) * 16) v = 0;
    val[i] = v;
    cuts |= v < 0;
  }
  return cuts;
}

// The part of `in` where the values are >= 0, some being < 0.
Cell clipped(const Cell& in, const Values& val) {
  const std::size_t n = in.v.size();
  Cell out;
  bool all_out = true;
  for (double v : val) all_out &= v <= 0;
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

}  // namespace

Cell clip(const Cell& in, const Affine& h) {
  if (in.v.size() < 3) return Cell{};
  Values val;
  return values_at(in, h, val) ? clipped(in, val) : in;
}

bool clip_in_place(Cell& c, const Affine& h) {
  if (c.v.size() < 3) return false;
  Values val;
  if (values_at(c, h, val)) c = clipped(c, val);
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
