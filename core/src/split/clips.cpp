#include "linf/split/clips.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "geometry/window_cut.hpp"

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
  if (count == 0) throw std::invalid_argument("a clip library needs at least one clip");
  const WindowCut layer_cut(layer);
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
    // The shapes that meet the window, merged and cut to it (KLayout: layer & window).
    const auto cut = layer_cut.cut(clip.window);
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

std::size_t write_clip_library(const ClipLibrarySpec& spec) {
  const ClipColumns& k = spec.clips;
  const std::size_t n = k.count;
  std::vector<std::size_t> first_marker(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (k.types[i] >= spec.type_names.size()) throw std::invalid_argument("a type beyond type_names");
    if (k.marker_counts[i] < 0) throw std::invalid_argument("a negative marker count");
    first_marker[i + 1] = first_marker[i] + std::size_t(k.marker_counts[i]);
  }
  if (4 * first_marker[n] != k.marker_values) throw std::invalid_argument("the marker boxes do not match the counts");
  const double dbu = spec.dbu;
  auto clip_at = [&](std::size_t i, Clip& c) {
    // As the plugin computed them: g.score * dbu and so on, then "%.4f" / "%.4g".
    const double* v = k.values + 4 * i;
    const ClipGauge g{k.ranks[i], spec.type_names[k.types[i]], v[1] * dbu, v[0] * dbu, v[2], v[3] * dbu};
    c.name = clip_name(spec.prefix, g);
    c.label = clip_label(g);
    for (int j = 0; j < 4; ++j) c.window[j] = k.windows[4 * i + j], c.line[j] = k.lines[4 * i + j];
    c.at = {k.at[2 * i], k.at[2 * i + 1]};
    c.markers.clear();
    for (std::size_t m = first_marker[i]; m < first_marker[i + 1]; ++m) {
      // As KLayout rounds a box given in micrometres (half away from zero).
      std::array<std::int64_t, 4> box{};
      for (int j = 0; j < 4; ++j) box[j] = std::llround(k.marker_boxes[4 * m + j] * dbu / dbu);
      c.markers.push_back(box);
    }
  };
  return write_clip_library(spec.path, dbu, spec.layer, spec.layers, n, clip_at);
}

}  // namespace linf
