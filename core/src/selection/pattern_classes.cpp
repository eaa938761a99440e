#include "linf/selection/pattern_classes.hpp"

#include <boost/polygon/polygon.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "geometry/window_cut.hpp"
#include "util/parallel.hpp"

namespace linf {

namespace {
namespace bp = boost::polygon;
using BPoint = bp::point_data<int>;
using BPolygon = bp::polygon_data<int>;
using BSet = bp::polygon_set_data<int>;

// The coverage grid of the filter: n x n cells over the window.
constexpr int kGrid = 8;

// A window's clip, in doubled coordinates about the window's centre (u = 2x - (x1 + x2)): the
// 8 symmetries then map the integer grid onto itself, whether the side is odd or even.
struct Clip {
  std::int64_t side = 0;           // the window's side (DBU); the clip spans [-side, side]^2
  std::vector<BPolygon> polygons;  // holes joined to their outlines by cut lines
  std::array<double, kGrid * kGrid> cells{};  // area in each cell, cell (i, j) at i + kGrid j
  double area = 0, perimeter = 0;
  bool manhattan = false;  // every edge axis-parallel: XORed as Boost.Polygon's 90-degree sets
};

// Windows whose clips are made at once (in parallel), then compared in order.
constexpr std::size_t kChunk = 4096;

// Area of a polygon (cut lines included: they add nothing) inside the box, by clipping it to the
// box's four half-planes in turn (Sutherland-Hodgman): the clipped ring may have zero-width
// bridges where the polygon is not convex, which add no area either.
double area_in(const std::vector<std::array<double, 2>>& ring, double x1, double y1, double x2, double y2) {
  std::vector<std::array<double, 2>> in = ring, out;
  auto clip = [&](int axis, double bound, bool keep_above) {
    out.clear();
    const std::size_t n = in.size();
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = in[i];
      const auto& q = in[(i + 1) % n];
      const bool pin = keep_above ? p[axis] >= bound : p[axis] <= bound;
      const bool qin = keep_above ? q[axis] >= bound : q[axis] <= bound;
      if (pin) out.push_back(p);
      if (pin != qin) {
        const double t = (bound - p[axis]) / (q[axis] - p[axis]);
        std::array<double, 2> r{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])};
        r[axis] = bound;
        out.push_back(r);
      }
    }
    in.swap(out);
  };
  clip(0, x1, true), clip(0, x2, false), clip(1, y1, true), clip(1, y2, false);
  double a = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto& p = in[i];
    const auto& q = in[(i + 1) % in.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * a;
}

void measure(Clip& c) {
  const double s = double(c.side), w = 2 * s / kGrid;
  for (const BPolygon& p : c.polygons) {
    std::vector<std::array<double, 2>> ring;
    for (const BPoint& v : p) ring.push_back({double(v.x()), double(v.y())});
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const auto& a = ring[i];
      const auto& b = ring[(i + 1) % ring.size()];
      c.perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
    }
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i)
        c.cells[std::size_t(i + kGrid * j)] += area_in(ring, -s + i * w, -s + j * w, -s + (i + 1) * w, -s + (j + 1) * w);
  }
  // The cut polygons are oriented one way (Boost.Polygon's get): a shape's cells sum positive.
  double total = 0;
  for (double& a : c.cells) total += a;
  if (total < 0)
    for (double& a : c.cells) a = -a;
  c.area = std::fabs(total);
}

// Symmetry k of the square about the origin: mirror x if k & 1, then rotate by 90 (k >> 1) degrees.
std::array<std::int64_t, 2> transform(int k, std::int64_t u, std::int64_t v) {
  if (k & 1) u = -u;
  for (int r = 0; r < (k >> 1); ++r) std::tie(u, v) = std::make_tuple(-v, u);
  return {u, v};
}

// The cell that cell (i, j) goes to under symmetry k (the grid is symmetric about the origin:
// cell centres at odd multiples of half a cell).
int cell_to(int k, int i, int j) {
  const auto c = transform(k, 2 * i - (kGrid - 1), 2 * j - (kGrid - 1));
  return int((c[0] + kGrid - 1) / 2) + kGrid * int((c[1] + kGrid - 1) / 2);
}

template <class Set = BSet>
Set set_of(const Clip& c, int k) {
  Set s;
  for (const BPolygon& p : c.polygons) {
    std::vector<BPoint> v;
    v.reserve(p.size());
    for (const BPoint& q : p) {
      const auto t = transform(k, q.x(), q.y());
      v.emplace_back(int(t[0]), int(t[1]));
    }
    if constexpr (std::is_same_v<Set, BSet>) {
      BPolygon tp;
      tp.set(v.begin(), v.end());
      s.insert(tp);
    } else {
      s.insert(polygon_90_of(v));
    }
  }
  return s;
}

// The area of the XOR of two clips under symmetry k of the second; exact (doubled units squared).
double xor_area(const Clip& c, const Clip& rep, int k) {
  using namespace bp::operators;
  if (c.manhattan && rep.manhattan) return double(bp::area(set_of<bp::polygon_90_set_data<int>>(c, 0) ^
                                                           set_of<bp::polygon_90_set_data<int>>(rep, k)));
  return double(bp::area(set_of(c, 0) ^ set_of(rep, k)));
}

}  // namespace

PatternClasses classify_patterns(const FlatPolygons& layer, const std::vector<std::array<std::int64_t, 4>>& windows,
                                 const ClassRule& rule, int threads) {
  using namespace bp::operators;
  if (rule.by == ClassRule::Area && !(rule.area_fraction >= 0))
    throw std::invalid_argument("the area fraction of a pattern must be 0 or more");
  if (rule.by == ClassRule::Edge && rule.edge < 0) throw std::invalid_argument("the edge displacement must be 0 or more");
  const WindowCut layer_cut(layer);
  auto clip_of = [&](const std::array<std::int64_t, 4>& b) {
    Clip c;
    c.side = b[2] - b[0];
    if (c.side <= 0 || b[3] - b[1] != c.side) throw std::invalid_argument("a pattern window must be a square");
    if (c.side > (std::int64_t(1) << 29)) throw std::invalid_argument("a pattern window larger than 2^29 DBU");
    const std::vector<BPolygon> cut = layer_cut.cut(b, &c.manhattan);
    const std::int64_t cx = b[0] + b[2], cy = b[1] + b[3];
    for (const BPolygon& q : cut) {
      std::vector<BPoint> v;
      v.reserve(q.size());
      for (const BPoint& p : q) v.emplace_back(int(2 * std::int64_t(p.x()) - cx), int(2 * std::int64_t(p.y()) - cy));
      c.polygons.emplace_back(v.begin(), v.end());
    }
    measure(c);
    return c;
  };

  PatternClasses out;
  out.of_window.reserve(windows.size());
  std::vector<Clip> reps, chunk;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    if (w % kChunk == 0) {
      // The clips of the next windows, made on every core: each depends on its window alone.
      chunk.assign(std::min(kChunk, windows.size() - w), Clip{});
      detail::parallel_for(chunk.size(), threads, [&](unsigned, std::size_t i) { chunk[i] = clip_of(windows[w + i]); });
    }
    Clip& c = chunk[w % kChunk];
    const double window_area = 4.0 * double(c.side) * double(c.side);  // doubled units
    const double e2 = 2.0 * double(rule.edge);
    int found = -1;
    for (std::size_t r = 0; r < reps.size() && found < 0; ++r) {
      const Clip& rep = reps[r];
      if (rep.side != c.side) continue;
      // The XOR's area is at least the cells' differences (and the totals' difference); with
      // nothing wider than e it is at most e times the perimeters (generously): both tests only
      // discard pairs that cannot match. The representative under symmetry k has in cell
      // cell_to(k, i, j) what it has in cell (i, j).
      const double bound = rule.by == ClassRule::Area ? rule.area_fraction * window_area + 1e-9 * window_area
                                                        : e2 * (c.perimeter + rep.perimeter) + 1e-9 * window_area;
      if (std::fabs(c.area - rep.area) > bound) continue;
      BSet mine;
      bool have_mine = false;
      for (int k = 0; k < 8 && found < 0; ++k) {
        double lower = 0;
        for (int j = 0; j < kGrid && lower <= bound; ++j)
          for (int i = 0; i < kGrid; ++i)
            lower += std::fabs(c.cells[std::size_t(cell_to(k, i, j))] - rep.cells[std::size_t(i + kGrid * j)]);
        if (lower > bound) continue;
        ++out.compared;
        if (rule.by == ClassRule::Area) {
          if (xor_area(c, rep, k) <= rule.area_fraction * window_area * (1 + 1e-12)) found = int(r);
        } else {
          using namespace bp::operators;
          if (!have_mine) mine = set_of(c, 0), have_mine = true;
          BSet x = mine ^ set_of(rep, k);
          if (rule.edge > 0) x.resize(-int(rule.edge));
          if (bp::area(x) == 0) found = int(r);
        }
      }
    }
    if (found < 0) {
      found = int(reps.size());
      reps.push_back(std::move(c));
      out.representative.push_back(std::int32_t(w));
      out.count.push_back(0);
    }
    out.of_window.push_back(found);
    ++out.count[std::size_t(found)];
  }
  return out;
}

}  // namespace linf
