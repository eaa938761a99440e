#include "window_cut.hpp"

#include <algorithm>
#include <climits>

namespace linf {

namespace bp = boost::polygon;

namespace {

bool axis_parallel(const std::int64_t* xy, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (xy[2 * i] != xy[2 * j] && xy[2 * i + 1] != xy[2 * j + 1]) return false;
  }
  return true;
}

void set_outline(bp::polygon_with_holes_data<int>& ph, const bp::polygon_data<int>& r) { ph.set(r.begin(), r.end()); }
void set_outline(bp::polygon_90_with_holes_data<int>& ph, const bp::polygon_90_data<int>& r) {
  ph.set_compact(r.begin_compact(), r.end_compact());
}

bp::polygon_data<int> plain_of(const std::vector<bp::point_data<int>>& v) { return bp::polygon_data<int>(v.begin(), v.end()); }

// The polygons met, merged and cut to the box, in one of Boost.Polygon's two set types: its
// 90-degree set is several times faster where every polygon met is Manhattan (the usual layer).
template <class Set, class WithHoles, class Hole, Hole (*ring_of)(const std::vector<bp::point_data<int>>&)>
std::vector<bp::polygon_data<int>> cut_in(const PolygonIndex& index, const std::vector<std::int32_t>& met,
                                          const std::array<std::int64_t, 4>& b) {
  using namespace bp::operators;
  Set set;
  std::vector<bp::point_data<int>> v;
  for (std::int32_t p : met) {
    WithHoles ph;
    std::vector<Hole> holes;
    bool empty = false;
    index.rings(std::size_t(p), [&](const std::int64_t* xy, std::size_t n, bool outer) {
      v.clear();
      for (std::size_t i = 0; i < n; ++i) v.emplace_back(int(xy[2 * i]), int(xy[2 * i + 1]));
      const Hole r = ring_of(v);
      if (outer) empty = r.size() == 0, set_outline(ph, r);
      else if (r.size() > 0) holes.push_back(r);
    });
    if (empty) continue;
    ph.set_holes(holes.begin(), holes.end());
    set.insert(ph);
  }
  set &= bp::rectangle_data<int>(int(b[0]), int(b[1]), int(b[2]), int(b[3]));
  std::vector<bp::polygon_data<int>> out;
  set.get(out);
  return out;
}

}  // namespace

WindowCut::WindowCut(const FlatPolygons& layer)
    : index_(layer), tree_(index_.size(), [&](std::size_t i) { return index_.box(i); }), manhattan_(index_.size()) {
  for (std::size_t p = 0; p < index_.size(); ++p) {
    bool m = true;
    index_.rings(p, [&](const std::int64_t* xy, std::size_t n, bool) { m = m && axis_parallel(xy, n); });
    manhattan_[p] = m;
  }
}

std::vector<bp::polygon_data<int>> WindowCut::cut(const std::array<std::int64_t, 4>& b, bool* manhattan) const {
  auto to32 = [](std::int64_t v) { return std::int32_t(std::clamp<std::int64_t>(v, INT32_MIN, INT32_MAX)); };
  std::vector<std::int32_t> met;
  bool all_90 = true;
  tree_.query({to32(b[0]), to32(b[1]), to32(b[2]), to32(b[3])}, [&](std::int32_t p) {
    met.push_back(p);
    all_90 = all_90 && manhattan_[std::size_t(p)];
  });
  if (manhattan) *manhattan = all_90;
  if (all_90)
    return cut_in<bp::polygon_90_set_data<int>, bp::polygon_90_with_holes_data<int>, bp::polygon_90_data<int>,
                  &polygon_90_of<bp::point_data<int>>>(index_, met, b);
  return cut_in<bp::polygon_set_data<int>, bp::polygon_with_holes_data<int>, bp::polygon_data<int>, &plain_of>(index_, met, b);
}

}  // namespace linf
