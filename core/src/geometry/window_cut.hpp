// A layer cut to windows: the shapes that meet a window, merged and cut to it, as KLayout's
// `layer & window` gives them. The clip libraries (split/clips.cpp) write these polygons and
// the pattern classes (selection/pattern_classes.cpp) compare them. Internal to the core.
#pragma once
#include <boost/polygon/polygon.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/util/box_tree.hpp"

namespace linf {

// A ring of axis-parallel edges as Boost.Polygon's 90-degree polygon, whose compact form lists
// every other coordinate and so needs every vertex to be a turn: repeated points and points on
// a straight run (a spike's tip too: it adds no area) are dropped, which Boost's own
// points-to-compact conversion does not do. An empty polygon where nothing of the ring is left.
template <class Point>
boost::polygon::polygon_90_data<int> polygon_90_of(const std::vector<Point>& ring) {
  std::vector<boost::polygon::point_data<int>> v;
  for (const Point& p : ring) {
    const boost::polygon::point_data<int> q(int(boost::polygon::x(p)), int(boost::polygon::y(p)));
    if (v.empty() || q != v.back()) v.push_back(q);
  }
  while (v.size() > 1 && v.front() == v.back()) v.pop_back();
  // Drop the middle of straight runs until none is left (a run may wrap around the start).
  for (bool changed = true; changed && v.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < v.size() && v.size() >= 3;) {
      const auto& a = v[(i + v.size() - 1) % v.size()];
      const auto& c = v[(i + 1) % v.size()];
      if ((a.x() == v[i].x() && v[i].x() == c.x()) || (a.y() == v[i].y() && v[i].y() == c.y()) || a == v[i]) {
        v.erase(v.begin() + std::ptrdiff_t(i));
        changed = true;
      } else {
        ++i;
      }
    }
  }
  boost::polygon::polygon_90_data<int> out;
  if (v.size() < 4) return out;
  std::vector<int> compact;
  compact.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) compact.push_back(i % 2 == 0 ? v[i].x() : v[i].y());
  out.set_compact(compact.begin(), compact.end());
  return out;
}

class WindowCut {
 public:
  // Indexes the layer's polygons by their boxes; `layer` must outlive this.
  explicit WindowCut(const FlatPolygons& layer);
  // The layer inside the window (x1, y1, x2, y2), merged, holes joined to their outlines by
  // cut lines (Boost.Polygon's polygon_data): no polygon for an empty window. `manhattan`, if
  // given, is set to whether every polygon met has only axis-parallel edges (then so has the cut).
  std::vector<boost::polygon::polygon_data<int>> cut(const std::array<std::int64_t, 4>& window,
                                                     bool* manhattan = nullptr) const;

 private:
  PolygonIndex index_;
  BoxTree tree_;
  std::vector<bool> manhattan_;  // per polygon: every edge of every ring axis-parallel
};

}  // namespace linf
