#include "linf/clips.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/polygon/polygon.hpp>

#include <cmath>
#include <stdexcept>

namespace linf {

namespace {
namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
namespace bp = boost::polygon;
using IPt = bg::model::point<std::int64_t, 2, bg::cs::cartesian>;
using IBox = bg::model::box<IPt>;
using Entry = std::pair<IBox, std::uint32_t>;
using BPoint = bp::point_data<int>;

constexpr std::int64_t kLimit = std::int64_t(1) << 30;

// Where each polygon's rings and points start in the flat arrays, and its box.
struct Index {
  std::vector<std::size_t> first_ring, first_point;  // per polygon, plus one past the end
  std::vector<Entry> boxes;
};

Index index_of(const FlatPolygons& in) {
  Index ix;
  std::size_t at = 0;
  for (std::size_t k = 0; k < in.n_rings; ++k) {
    const std::int64_t c = in.rings[k];
    const std::size_t n = std::size_t(c < 0 ? -c : c);
    if (at + n > in.n_points) throw std::invalid_argument("rings count more points than there are");
    if (c >= 0) {
      ix.first_ring.push_back(k), ix.first_point.push_back(at);
      std::int64_t x1 = kLimit, y1 = kLimit, x2 = -kLimit, y2 = -kLimit;
      for (std::size_t i = at; i < at + n; ++i) {
        const std::int64_t x = in.points[2 * i], y = in.points[2 * i + 1];
        if (x <= -kLimit || x >= kLimit || y <= -kLimit || y >= kLimit)
          throw std::invalid_argument("coordinate outside +-2^30 database units");
        x1 = std::min(x1, x), y1 = std::min(y1, y), x2 = std::max(x2, x), y2 = std::max(y2, y);
      }
      if (n > 0) ix.boxes.push_back({IBox(IPt(x1, y1), IPt(x2, y2)), std::uint32_t(ix.first_ring.size() - 1)});
    } else if (ix.first_ring.empty()) {
      throw std::invalid_argument("a hole (negative count) must follow its outer ring");
    }
    at += n;
  }
  ix.first_ring.push_back(in.n_rings), ix.first_point.push_back(at);
  return ix;
}

std::vector<BPoint> ring_points(const FlatPolygons& in, std::size_t first, std::size_t n) {
  std::vector<BPoint> v;
  v.reserve(n);
  for (std::size_t i = first; i < first + n; ++i) v.emplace_back(int(in.points[2 * i]), int(in.points[2 * i + 1]));
  return v;
}

Ring box_ring(const std::array<std::int64_t, 4>& b) {
  return {{b[0], b[1]}, {b[2], b[1]}, {b[2], b[3]}, {b[0], b[3]}};
}

}  // namespace

std::size_t write_clip_library(const std::string& path, double dbu, const FlatPolygons& layer,
                               const ClipLayers& l, const std::vector<Clip>& clips) {
  using namespace bp::operators;
  if (clips.empty()) throw std::invalid_argument("a clip library needs at least one clip");
  const Index ix = index_of(layer);
  const bgi::rtree<Entry, bgi::rstar<16>> tree(ix.boxes.begin(), ix.boxes.end());
  OasisWriter w(path, dbu, clips.front().name);
  w.layer_name("gauges", l.layer, l.gauges);
  w.layer_name("windows", l.layer, l.windows);
  w.layer_name("markers", l.layer, l.markers);
  std::size_t shapes = 0;
  std::vector<Entry> near;
  for (std::size_t c = 0; c < clips.size(); ++c) {
    const Clip& clip = clips[c];
    if (c > 0) w.cell(clip.name);
    const auto& b = clip.window;
    // The shapes that meet the window, merged and cut to it (KLayout: layer & window).
    near.clear();
    tree.query(bgi::intersects(IBox(IPt(b[0], b[1]), IPt(b[2], b[3]))), std::back_inserter(near));
    bp::polygon_set_data<int> set;
    for (const Entry& e : near) {
      const std::size_t p = e.second;
      std::size_t at = ix.first_point[p];
      bp::polygon_with_holes_data<int> ph;
      std::vector<bp::polygon_data<int>> holes;
      for (std::size_t k = ix.first_ring[p]; k < ix.first_ring[p + 1]; ++k) {
        const std::size_t n = std::size_t(std::llabs(layer.rings[k]));
        const std::vector<BPoint> v = ring_points(layer, at, n);
        if (k == ix.first_ring[p]) ph.set(v.begin(), v.end());
        else holes.emplace_back(v.begin(), v.end());
        at += n;
      }
      ph.set_holes(holes.begin(), holes.end());
      set.insert(ph);
    }
    set &= bp::rectangle_data<int>(int(b[0]), int(b[1]), int(b[2]), int(b[3]));
    std::vector<bp::polygon_data<int>> cut;  // holes joined to their outlines by cut lines
    set.get(cut);
    for (const auto& q : cut) {
      Ring r;
      for (const BPoint& v : q) r.push_back({v.x(), v.y()});
      if (r.size() > 1 && r.front() == r.back()) r.pop_back();
      w.polygon(l.layer, l.datatype, r), ++shapes;
    }
    w.path(l.layer, l.gauges, clip.line[0], clip.line[1], clip.line[2], clip.line[3]);
    w.text(l.layer, l.gauges, clip.at[0], clip.at[1], clip.label);
    w.polygon(l.layer, l.windows, box_ring(clip.window));
    for (const auto& m : clip.markers) w.polygon(l.layer, l.markers, box_ring(m));
    shapes += 3 + clip.markers.size();
  }
  w.close();
  return shapes;
}

}  // namespace linf
