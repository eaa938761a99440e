#include <CGAL/Segment_Delaunay_graph_Linf_2.h>
#include <CGAL/Segment_Delaunay_graph_Linf_filtered_traits_2.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <numeric>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "linf/geometry/distance.hpp"
#include "linf/baseline/cgal_baseline.hpp"

namespace linf {
namespace {

using CK = CGAL::Simple_cartesian<double>;
// Non-intersecting sites: merged polygon boundaries only meet at shared endpoints.
using Gt = CGAL::Segment_Delaunay_graph_Linf_filtered_traits_without_intersections_2<CK>;
using SDG = CGAL::Segment_Delaunay_graph_Linf_2<Gt>;

struct PointHash {
  std::size_t operator()(const std::pair<double, double>& p) const {
    return std::hash<double>()(p.first) * 1000003u ^ std::hash<double>()(p.second);
  }
};
struct SegHash {
  std::size_t operator()(const std::array<double, 4>& s) const {
    std::size_t h = 0;
    for (double v : s) h = h * 1000003u ^ std::hash<double>()(v);
    return h;
  }
};

class SiteIndex {
 public:
  explicit SiteIndex(const Sites& s) {
    for (std::size_t i = 0; i < s.sites.size(); ++i) {
      const Site& t = s.sites[i];
      if (t.is_point())
        points_.emplace(std::make_pair(double(t.a.x), double(t.a.y)), std::int32_t(i));
      else
        segs_.emplace(key(double(t.a.x), double(t.a.y), double(t.b.x), double(t.b.y)), std::int32_t(i));
    }
  }
  std::int32_t find(const SDG::Site_2& s) const {
    if (s.is_point()) {
      auto it = points_.find({s.point().x(), s.point().y()});
      if (it == points_.end()) throw std::runtime_error("CGAL returned an unknown point site");
      return it->second;
    }
    auto it = segs_.find(key(s.source().x(), s.source().y(), s.target().x(), s.target().y()));
    if (it == segs_.end()) throw std::runtime_error("CGAL returned an unknown segment site");
    return it->second;
  }

 private:
  static std::array<double, 4> key(double x1, double y1, double x2, double y2) {
    if (std::make_pair(x2, y2) < std::make_pair(x1, y1)) return {x2, y2, x1, y1};
    return {x1, y1, x2, y2};
  }
  std::unordered_map<std::pair<double, double>, std::int32_t, PointHash> points_;
  std::unordered_map<std::array<double, 4>, std::int32_t, SegHash> segs_;
};

Vec2 to_vec(const CK::Point_2& p) { return {p.x(), p.y()}; }
Vec2 to_vec(const CK::Direction_2& d) { return {d.dx(), d.dy()}; }

}  // namespace

namespace {
struct CgalInput {
  std::vector<CK::Point_2> pts;
  std::vector<std::pair<std::size_t, std::size_t>> segs;
};
}  // namespace

static CgalInput cgal_input(const Sites& sites, std::uint64_t order_seed) {
  CgalInput in;
  auto& pts = in.pts;
  std::unordered_map<std::pair<double, double>, std::size_t, PointHash> point_slot;
  auto slot = [&](const Point& p) {
    auto k = std::make_pair(double(p.x), double(p.y));
    auto [it, fresh] = point_slot.emplace(k, pts.size());
    if (fresh) pts.emplace_back(k.first, k.second);
    return it->second;
  };
  auto& segs = in.segs;
  for (const Site& s : sites.sites) {
    if (s.is_point())
      slot(s.a);
    else
      segs.emplace_back(slot(s.a), slot(s.b));
  }
  if (order_seed != 0) {
    std::mt19937_64 rng(order_seed);
    std::shuffle(segs.begin(), segs.end(), rng);
  }
  return in;
}

double cgal_linf_construction_seconds(const Sites& sites, std::uint64_t order_seed) {
  CgalInput in = cgal_input(sites, order_seed);
  const auto t0 = std::chrono::steady_clock::now();
  SDG sdg;
  sdg.insert_segments(in.pts, in.segs.begin(), in.segs.end());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<RawEdge> cgal_linf_edges(const Sites& sites, std::uint64_t order_seed) {
  CgalInput in = cgal_input(sites, order_seed);
  auto& pts = in.pts;
  auto& segs = in.segs;
  SDG sdg;
  // Range insertion: points spatially sorted, then segments between existing vertices.
  // Inserting one by one into the hierarchy can hang (foundation issue, case 4).
  sdg.insert_segments(pts, segs.begin(), segs.end());

  SiteIndex index(sites);
  std::vector<RawEdge> out;
  out.reserve(sdg.number_of_vertices() * 3);
  for (auto eit = sdg.finite_edges_begin(); eit != sdg.finite_edges_end(); ++eit) {
    const SDG::Edge e = *eit;
    RawEdge r;
    r.a = index.find(e.first->vertex(SDG::ccw(e.second))->site());
    r.b = index.find(e.first->vertex(SDG::cw(e.second))->site());
    CGAL::Object o = sdg.primal(e);
    CGAL::Polychainline_2<Gt> pcl;
    CGAL::Polychainray_2<Gt> pcr;
    CGAL::Polychainsegment_2<Gt> pcs;
    if (CGAL::assign(pcl, o)) {
      for (auto v = pcl.vertices_begin(); v != pcl.vertices_end(); ++v) r.pts.push_back(to_vec(*v));
      r.ray_in = r.ray_out = true;
      r.dir_in = to_vec(pcl.get_incoming());
      r.dir_out = to_vec(pcl.get_outgoing());
    } else if (CGAL::assign(pcr, o)) {
      for (auto v = pcr.vertices_begin(); v != pcr.vertices_end(); ++v) r.pts.push_back(to_vec(*v));
      r.ray_out = true;
      r.dir_out = to_vec(pcr.get_outgoing());
    } else if (CGAL::assign(pcs, o)) {
      for (auto v = pcs.vertices_begin(); v != pcs.vertices_end(); ++v) r.pts.push_back(to_vec(*v));
    } else {
      continue;  // an edge CGAL cannot draw; the checker's crossing test will notice a gap
    }
    if (!r.pts.empty()) out.push_back(std::move(r));
  }
  return out;
}


namespace {
// Liang-Barsky clip of p + t (q - p), t in [t0, t1].
bool clip_segment(const Box& b, Vec2& p, Vec2& q, double t1max) {
  double t0 = 0, t1 = t1max;
  const double dx = q.x - p.x, dy = q.y - p.y;
  auto edge = [&](double pp, double qq) {
    if (pp == 0) return qq >= 0;
    const double r = qq / pp;
    if (pp < 0) { if (r > t1) return false; t0 = std::max(t0, r); }
    else { if (r < t0) return false; t1 = std::min(t1, r); }
    return true;
  };
  if (!(edge(-dx, p.x - b.x1) && edge(dx, b.x2 - p.x) && edge(-dy, p.y - b.y1) && edge(dy, b.y2 - p.y))) return false;
  const Vec2 a{p.x + t0 * dx, p.y + t0 * dy}, c{p.x + t1 * dx, p.y + t1 * dy};
  p = a, q = c;
  return t1 > t0;
}
}  // namespace

std::vector<Piece> cgal_linf_pieces(const Sites& sites, const Box& clip, std::uint64_t order_seed) {
  std::vector<Piece> out;
  const double far = 4 * std::max(clip.x2 - clip.x1, clip.y2 - clip.y1);
  auto add = [&](std::int32_t a, std::int32_t b, Vec2 p, Vec2 q, double tmax) {
    if (!clip_segment(clip, p, q, tmax)) return;
    Piece pc;
    pc.p = p, pc.q = q, pc.a = a, pc.b = b;
    pc.d1 = dist_site(p.x, p.y, sites.sites[a]);
    pc.d2 = dist_site(q.x, q.y, sites.sites[a]);
    out.push_back(pc);
  };
  for (const RawEdge& e : cgal_linf_edges(sites, order_seed)) {
    auto ray = [&](const Vec2& from, const Vec2& dir) {
      const double len = std::hypot(dir.x, dir.y);
      add(e.a, e.b, from, {from.x + dir.x / len * far, from.y + dir.y / len * far}, 1.0);
    };
    if (e.ray_in) ray(e.pts.front(), e.dir_in);
    for (std::size_t i = 0; i + 1 < e.pts.size(); ++i) add(e.a, e.b, e.pts[i], e.pts[i + 1], 1.0);
    if (e.ray_out) ray(e.pts.back(), e.dir_out);
  }
  return out;
}

}  // namespace linf
