#include "window_cut.hpp"

#include <algorithm>
#include <climits>

namespace linf {

namespace bp = boost::polygon;

WindowCut::WindowCut(const FlatPolygons& layer)
    : index_(layer), tree_(index_.size(), [&](std::size_t i) { return index_.box(i); }) {}

std::vector<bp::polygon_data<int>> WindowCut::cut(const std::array<std::int64_t, 4>& b) const {
  using namespace bp::operators;
  bp::polygon_set_data<int> set;
  auto to32 = [](std::int64_t v) { return std::int32_t(std::clamp<std::int64_t>(v, INT32_MIN, INT32_MAX)); };
  tree_.query({to32(b[0]), to32(b[1]), to32(b[2]), to32(b[3])}, [&](std::int32_t p) {
    bp::polygon_with_holes_data<int> ph;
    std::vector<bp::polygon_data<int>> holes;
    index_.rings(std::size_t(p), [&](const std::int64_t* xy, std::size_t n, bool outer) {
      std::vector<bp::point_data<int>> v;
      v.reserve(n);
      for (std::size_t i = 0; i < n; ++i) v.emplace_back(int(xy[2 * i]), int(xy[2 * i + 1]));
      if (outer) ph.set(v.begin(), v.end());
      else holes.emplace_back(v.begin(), v.end());
    });
    ph.set_holes(holes.begin(), holes.end());
    set.insert(ph);
  });
  set &= bp::rectangle_data<int>(int(b[0]), int(b[1]), int(b[2]), int(b[3]));
  std::vector<bp::polygon_data<int>> out;
  set.get(out);
  return out;
}

}  // namespace linf
