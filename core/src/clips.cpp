#include "linf/clips.hpp"

#include <boost/polygon/polygon.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace linf {

namespace bp = boost::polygon;
using BPoint = bp::point_data<int>;

// The plugin named and labelled clips with Python's "%.4f" and "%.4g": C's printf rounds the
// same double the same way (both exactly), so the files stay as they were.
std::string clip_name(std::string_view set_prefix, const ClipGauge& g) {
  char score[64];
  std::snprintf(score, sizeof score, "%.4f", g.score_um);
  std::string s = score;
  std::replace(s.begin(), s.end(), '.', 'p');
  std::replace(s.begin(), s.end(), '-', 'm');
  char rank[32];
  std::snprintf(rank, sizeof rank, "%06lld", static_cast<long long>(g.rank));
  return std::string(set_prefix) + "_r" + rank + "_" + std::string(g.type) + "_" + s;
}

std::string clip_label(const ClipGauge& g) {
  const std::string type(g.type);
  char buf[256];
  std::snprintf(buf, sizeof buf, "#%lld %s cd=%.4g score=%.4g norm=%.4g tiebreak=%.4g", static_cast<long long>(g.rank),
                type.c_str(), g.cd_um, g.score_um, g.norm_score, g.tiebreak_um);
  return buf;
}

std::size_t write_clip_library(const std::string& path, double dbu, const FlatPolygons& layer,
                               const ClipLayers& l, std::size_t count, const ClipSource& clip_at) {
  using namespace bp::operators;
  if (count == 0) throw std::invalid_argument("a clip library needs at least one clip");
  const PolygonIndex ix(layer);
  const BoxTree tree(ix.size(), [&](std::size_t i) { return ix.box(i); });
  Clip clip;
  clip_at(0, clip);
  OasisWriter w(path, dbu, clip.name);
  w.layer_name("gauges", l.layer, l.gauges);
  w.layer_name("windows", l.layer, l.windows);
  w.layer_name("markers", l.layer, l.markers);
  std::size_t shapes = 0;
  for (std::size_t c = 0; c < count; ++c) {
    if (c > 0) {
      clip_at(c, clip);
      w.cell(clip.name);
    }
    const auto& b = clip.window;
    // The shapes that meet the window, merged and cut to it (KLayout: layer & window).
    bp::polygon_set_data<int> set;
    auto to32 = [](std::int64_t v) { return std::int32_t(std::clamp<std::int64_t>(v, INT32_MIN, INT32_MAX)); };
    tree.query({to32(b[0]), to32(b[1]), to32(b[2]), to32(b[3])}, [&](std::int32_t p) {
      bp::polygon_with_holes_data<int> ph;
      std::vector<bp::polygon_data<int>> holes;
      ix.rings(std::size_t(p), [&](const std::int64_t* xy, std::size_t n, bool outer) {
        std::vector<BPoint> v;
        v.reserve(n);
        for (std::size_t i = 0; i < n; ++i) v.emplace_back(int(xy[2 * i]), int(xy[2 * i + 1]));
        if (outer) ph.set(v.begin(), v.end());
        else holes.emplace_back(v.begin(), v.end());
      });
      ph.set_holes(holes.begin(), holes.end());
      set.insert(ph);
    });
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
