#include "linf/diagram/diagram.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "linf/diagram/classify.hpp"
#include "linf/diagram/sweep.hpp"
#include "linf/geometry/sites.hpp"

namespace linf {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Result finish(Sites sites, const DiagramOptions& opt, double seconds_merge) {
  Result r;
  Diagram& d = r.diagram;
  d.seconds_merge = seconds_merge;
  d.sites = std::move(sites);
  d.clip = clip_box(d.sites);
  auto t0 = std::chrono::steady_clock::now();
  BuildStats st;
  BuildOptions build = opt.build;
  build.sweep = d.swept = opt.sweep && sweep_handles(d.sites);
  d.pieces = build_pieces(d.sites, d.clip, build, &st, opt.progress);
  d.tiles = st.tiles, d.tile_tasks = st.tasks, d.largest_tile_sites = st.largest_tile_sites;
  for (Piece& p : d.pieces) p.kind = classify(d.sites, p);
  d.seconds_build = since(t0);
  d.attempts = 1;
  if (opt.check) {
    if (opt.progress) opt.progress("checking the diagram", 0, 0);
    t0 = std::chrono::steady_clock::now();
    CheckOptions co = opt.checker;
    co.threads = opt.build.threads;
    r.check = check_diagram(d, co);
    d.seconds_check = since(t0);
    if (!r.check.ok()) {
      std::string what = "the L-inf Voronoi diagram failed its check";
      if (!r.check.messages.empty()) what += ": " + r.check.messages.front();
      throw DiagramError(what, r.check);
    }
  }
  return r;
}
}  // namespace

Box clip_box(const Sites& s) {
  if (s.sites.empty()) return {};
  double x1 = INFINITY, y1 = INFINITY, x2 = -INFINITY, y2 = -INFINITY;
  for (const Site& t : s.sites)
    for (const Point& p : {t.a, t.b}) {
      x1 = std::min(x1, double(p.x)), y1 = std::min(y1, double(p.y));
      x2 = std::max(x2, double(p.x)), y2 = std::max(y2, double(p.y));
    }
  const double m = std::max({x2 - x1, y2 - y1, 1.0});
  return {x1 - m, y1 - m, x2 + m, y2 + m};
}

Result voronoi_of_polygons(const FlatPolygons& polygons, const DiagramOptions& opt) {
  auto t0 = std::chrono::steady_clock::now();
  Sites s = sites_of_polygons(merge_polygons(polygons, std::size_t(1) << 16, opt.build.threads).view());
  return finish(std::move(s), opt, since(t0));
}

Result voronoi_of_polygons(const std::vector<Polygon>& polygons, const DiagramOptions& opt) {
  return voronoi_of_polygons(flat_of(polygons).view(), opt);
}

Result voronoi_of_sites(const std::vector<Point>& points, const std::vector<Segment>& segments,
                        const DiagramOptions& opt) {
  return finish(sites_of_plain(points, segments), opt, 0);
}

}  // namespace linf
