#include "linf/farthest/farthest.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "linf/geometry/distance.hpp"

namespace linf {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using P3 = K::Point_3;
using V3 = K::Vector_3;
using Mesh = CGAL::Surface_mesh<P3>;

// The double nearest to an exact number. CGAL::to_double of a lazy number gives a point of
// its interval approximation (off by up to about 1e-11 of the magnitude), and that of the
// exact type may truncate (GMP's mpq_get_d): from there, a step to a neighbour that lies
// nearer, decided exactly.
double nearest(const FT& v) {
  const auto& e = CGAL::exact(v);
  using ET = std::decay_t<decltype(e)>;
  double d = CGAL::to_double(e);
  for (int step = 0; step < 4; ++step) {
    const double up = std::nextafter(d, INFINITY), down = std::nextafter(d, -INFINITY);
    if (e > (ET(d) + ET(up)) / 2) d = up;
    else if (e < (ET(d) + ET(down)) / 2) d = down;
    else break;
  }
  return d;
}

// One affine piece of the farthest distance: (n.x - h) / (|n_x| + |n_y|), the highest of all
// sites' pieces with this normal, owned by every site attaining it.
struct Plane {
  std::int64_t nx = 0, ny = 0, h = 0;
  std::vector<std::int32_t> owners;
  // Lazy exact numbers take `long` (64 bits here), not `long long`.
  FT l1() const { return FT(long(std::llabs(nx) + std::llabs(ny))); }
  FT a() const { return FT(long(nx)) / l1(); }
  FT b() const { return FT(long(ny)) / l1(); }
  FT c() const { return FT(long(-h)) / l1(); }
  Vec2 direction() const {  // where the piece is the highest far away
    if (nx == 0 || ny == 0) return {double((nx > 0) - (nx < 0)), double((ny > 0) - (ny < 0))};
    const double r = std::sqrt(0.5);
    return {nx > 0 ? r : -r, ny > 0 ? r : -r};
  }
};

std::int64_t cross(const Point& o, const Point& a, const Point& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Convex hull, counter-clockwise, no repeated or collinear points (monotone chain).
std::vector<Point> hull_of(std::vector<Point> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Point> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

std::vector<Plane> planes_of(const std::vector<std::vector<Point>>& sites) {
  std::map<std::pair<std::int64_t, std::int64_t>, Plane> best;
  for (std::int32_t s = 0; s < std::int32_t(sites.size()); ++s) {
    const std::vector<Point> h = hull_of(sites[s]);
    if (h.empty()) throw std::invalid_argument("farthest_voronoi: a site without points");
    for (const Point& q : h)
      if (std::llabs(q.x) >= (1LL << 30) || std::llabs(q.y) >= (1LL << 30))
        throw std::invalid_argument("farthest_voronoi: coordinates must stay below 2^30");
    std::vector<std::pair<std::int64_t, std::int64_t>> normals{{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (std::size_t i = 0; h.size() >= 2 && i < h.size(); ++i) {
      const Point& p = h[i];
      const Point& q = h[(i + 1) % h.size()];
      std::int64_t nx = q.y - p.y, ny = p.x - q.x;  // outward for a counter-clockwise ring
      const std::int64_t g = std::gcd(std::llabs(nx), std::llabs(ny));
      nx /= g, ny /= g;
      if (nx != 0 && ny != 0) normals.push_back({nx, ny});
      if (h.size() == 2 && nx != 0 && ny != 0) normals.push_back({-nx, -ny});  // a segment: both sides
      if (h.size() == 2) break;
    }
    for (auto [nx, ny] : normals) {
      std::int64_t hs = nx * h[0].x + ny * h[0].y;
      for (const Point& q : h) hs = std::max(hs, nx * q.x + ny * q.y);
      auto it = best.find({nx, ny});
      if (it == best.end()) {
        best[{nx, ny}] = Plane{nx, ny, hs, {s}};
      } else if (hs < it->second.h) {
        it->second.h = hs, it->second.owners = {s};
      } else if (hs == it->second.h) {
        it->second.owners.push_back(s);
      }
    }
  }
  std::vector<Plane> out;
  for (auto& [k, p] : best) out.push_back(std::move(p));
  return out;
}

// Pieces whose gradient lies inside one side of the gradient diamond (|a| + |b| = 1) have their
// dual points in one vertical plane; only the upper convex chain of those points, between the
// side's two corner (axis) pieces, can reach the upper hull. Keeping only those chains leaves
// the 3D hull a handful of points for random input.
std::vector<Plane> upper_chains(std::vector<Plane> planes) {
  using P2 = K::Point_2;
  std::vector<Plane> out;
  std::vector<std::vector<std::size_t>> side(4);
  std::map<std::pair<std::int64_t, std::int64_t>, std::size_t> corner;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const Plane& p = planes[i];
    if (p.nx == 0 || p.ny == 0) {
      corner[{p.nx, p.ny}] = i;
      out.push_back(p);
    } else {
      side[(p.nx > 0 ? 0 : 1) + (p.ny > 0 ? 0 : 2)].push_back(i);
    }
  }
  const std::pair<std::int64_t, std::int64_t> ends[4][2] = {
      {{1, 0}, {0, 1}}, {{-1, 0}, {0, 1}}, {{1, 0}, {0, -1}}, {{-1, 0}, {0, -1}}};
  for (int k = 0; k < 4; ++k) {
    if (side[k].empty()) continue;
    std::vector<std::pair<P2, std::size_t>> pts;
    for (auto e : ends[k]) {
      const Plane& c = planes[corner.at(e)];
      pts.push_back({P2(c.a(), c.c()), std::size_t(-1)});
    }
    for (std::size_t i : side[k]) pts.push_back({P2(planes[i].a(), planes[i].c()), i});
    std::sort(pts.begin(), pts.end(), [](auto& u, auto& v) { return CGAL::compare_xy(u.first, v.first) == CGAL::SMALLER; });
    std::vector<std::pair<P2, std::size_t>> chain;
    for (auto& q : pts) {
      while (chain.size() >= 2 &&
             CGAL::orientation(chain[chain.size() - 2].first, chain.back().first, q.first) != CGAL::RIGHT_TURN)
        chain.pop_back();
      chain.push_back(q);
    }
    for (auto& q : chain)
      if (q.second != std::size_t(-1)) out.push_back(planes[q.second]);
  }
  return out;
}

struct Lexi {
  bool operator()(const P3& u, const P3& v) const { return CGAL::compare_xyz(u, v) == CGAL::SMALLER; }
};

struct Builder {
  std::vector<Plane> planes;
  FarthestDiagram d;
  std::vector<FT> weight;                   // exact vertex weights
  std::vector<std::pair<FT, FT>> position;  // exact vertex positions
  std::vector<std::int32_t> face_of_plane;

  std::int32_t vertex_at(const FT& x, const FT& y, const FT& w, std::map<std::pair<FT, FT>, std::int32_t>& index) {
    auto [it, fresh] = index.try_emplace({x, y}, std::int32_t(d.vertices.size()));
    if (fresh) {
      d.vertices.push_back({{nearest(x), nearest(y)}, nearest(w), {}});
      weight.push_back(w);
      position.push_back({x, y});
    }
    return it->second;
  }

  // Faces: one per envelope piece, merged across edges whose pieces have the same owners.
  std::vector<std::int32_t> parent;
  std::int32_t find(std::int32_t i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }

  void finish(std::vector<std::array<std::int32_t, 4>>& raw_edges, const std::vector<Vec2>& ray_dirs,
              const std::vector<char>& used) {
    parent.resize(planes.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (auto& e : raw_edges)
      if (planes[e[0]].owners == planes[e[1]].owners) parent[find(e[0])] = find(e[1]);
    face_of_plane.assign(planes.size(), -1);
    for (std::size_t i = 0; i < planes.size(); ++i) {
      if (!used[i]) continue;
      const std::int32_t r = find(std::int32_t(i));
      if (face_of_plane[r] < 0) {
        face_of_plane[r] = std::int32_t(d.faces.size());
        d.faces.push_back({planes[r].owners, planes[r].direction(), 0});
      }
      face_of_plane[i] = face_of_plane[r];
      ++d.faces[face_of_plane[i]].pieces;
      ++d.hull_pieces;
    }
    for (std::size_t k = 0; k < raw_edges.size(); ++k) {
      auto& e = raw_edges[k];
      const std::int32_t fa = face_of_plane[e[0]], fb = face_of_plane[e[1]];
      if (fa == fb) continue;
      d.edges.push_back({fa, fb, e[2], e[3], ray_dirs[k]});
      for (std::int32_t v : {e[2], e[3]})
        if (v >= 0) {
          auto& fs = d.vertices[v].faces;
          for (std::int32_t f : {fa, fb})
            if (std::find(fs.begin(), fs.end(), f) == fs.end()) fs.push_back(f);
        }
    }
    // The root: the least weight, at a vertex or along an edge whose ends both have it.
    std::size_t best = 0;
    for (std::size_t v = 1; v < weight.size(); ++v)
      if (weight[v] < weight[best]) best = v;
    d.root.p = d.root.q = d.vertices[best].at;
    d.root.half_side = d.vertices[best].weight;
    for (const FarthestEdge& e : d.edges)
      if (e.to >= 0 && weight[e.from] == weight[best] && weight[e.to] == weight[best]) {
        d.root.p = d.vertices[e.from].at;
        d.root.q = d.vertices[e.to].at;
        break;
      }
  }
};

Vec2 unit(double x, double y) {
  const double l = std::hypot(x, y);
  return l > 0 ? Vec2{x / l, y / l} : Vec2{0, 0};
}

}  // namespace

FarthestDiagram farthest_voronoi(const std::vector<std::vector<Point>>& sites) {
  if (sites.empty()) return {};
  Builder b;
  b.planes = upper_chains(planes_of(sites));
  const auto& P = b.planes;
  std::vector<P3> pts;
  std::map<P3, std::int32_t, Lexi> id;
  for (std::size_t i = 0; i < P.size(); ++i) {
    pts.push_back(P3(P[i].a(), P[i].b(), P[i].c()));
    id[pts.back()] = std::int32_t(i);
  }
  std::vector<std::array<std::int32_t, 4>> raw;  // plane, plane, vertex, vertex (-1: ray)
  std::vector<Vec2> dirs;
  std::vector<char> used(P.size(), 0);
  std::map<std::pair<FT, FT>, std::int32_t> index;

  // Every piece through one point: one vertex, and rays between pieces neighbouring in the
  // order of their normals (the four bounding lines always make the dual points span a plane).
  // The four axis pieces' gradients (+-1, 0), (0, +-1) are not collinear, so three dual points
  // that are not collinear exist.
  std::size_t k2 = 2;
  while (k2 < pts.size() && CGAL::collinear(pts[0], pts[1], pts[k2])) ++k2;
  if (k2 == pts.size()) {
    std::swap(pts[1], pts[2]);
    for (k2 = 2; k2 < pts.size() && CGAL::collinear(pts[0], pts[1], pts[k2]);) ++k2;
  }
  bool flat = true;
  for (std::size_t i = 1; i < pts.size() && flat; ++i) flat = CGAL::coplanar(pts[0], pts[1], pts[k2], pts[i]);
  if (flat) {
    V3 n = CGAL::cross_product(pts[1] - pts[0], pts[k2] - pts[0]);
    if (n.z() < 0) n = -n;
    const FT x = n.x() / n.z(), y = n.y() / n.z();
    const FT w = pts[0].x() * x + pts[0].y() * y + pts[0].z();
    const std::int32_t v = b.vertex_at(x, y, w, index);
    std::vector<std::int32_t> order(P.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::int32_t i, std::int32_t j) {
      return std::atan2(double(P[i].ny), double(P[i].nx)) < std::atan2(double(P[j].ny), double(P[j].nx));
    });
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::int32_t i = order[k], j = order[(k + 1) % order.size()];
      used[i] = 1;
      const double ai = nearest(P[i].a()), bi = nearest(P[i].b());
      const double aj = nearest(P[j].a()), bj = nearest(P[j].b());
      Vec2 dir = unit(-(bj - bi), aj - ai);  // perpendicular to the gradient difference
      if (dir.x * (ai + aj) + dir.y * (bi + bj) < 0) dir = {-dir.x, -dir.y};
      raw.push_back({i, j, v, -1});
      dirs.push_back(dir);
    }
    b.finish(raw, dirs, used);
    return b.d;
  }

  Mesh m;
  CGAL::convex_hull_3(pts.begin(), pts.end(), m);
  // Upper facets are the diagram's vertices: a facet with outward normal (x, y, w), w > 0, is
  // where its pieces are highest, at (x / w, y / w).
  std::map<Mesh::Face_index, std::int32_t> vertex_of;
  std::map<Mesh::Face_index, V3> normal_of;
  for (Mesh::Face_index f : m.faces()) {
    auto h = m.halfedge(f);
    const P3& p0 = m.point(m.source(h));
    const P3& p1 = m.point(m.target(h));
    const P3& p2 = m.point(m.target(m.next(h)));
    const V3 n = CGAL::cross_product(p1 - p0, p2 - p0);
    normal_of[f] = n;
    if (CGAL::is_positive(n.z())) {
      const FT x = n.x() / n.z(), y = n.y() / n.z();
      vertex_of[f] = b.vertex_at(x, y, p0.x() * x + p0.y() * y + p0.z(), index);
    }
  }
  for (Mesh::Edge_index e : m.edges()) {
    auto h = m.halfedge(e);
    Mesh::Face_index f1 = m.face(h), f2 = m.face(m.opposite(h));
    auto u1 = vertex_of.find(f1), u2 = vertex_of.find(f2);
    if (u1 == vertex_of.end() && u2 == vertex_of.end()) continue;
    const std::int32_t i = id.at(m.point(m.source(h))), j = id.at(m.point(m.target(h)));
    used[i] = used[j] = 1;
    if (u1 != vertex_of.end() && u2 != vertex_of.end()) {
      if (u1->second == u2->second) continue;  // inside a vertex where more than three pieces meet
      raw.push_back({i, j, u1->second, u2->second});
      dirs.push_back({0, 0});
      continue;
    }
    if (u1 == vertex_of.end()) std::swap(f1, f2), std::swap(u1, u2);
    // A ray: the edge's normal cone meets w = 0 in the direction w1 n2 - w2 n1.
    const V3& n1 = normal_of[f1];
    const V3& n2 = normal_of[f2];
    const V3 r = n1.z() * n2 - n2.z() * n1;
    raw.push_back({i, j, u1->second, -1});
    dirs.push_back(unit(nearest(r.x()), nearest(r.y())));
  }
  b.finish(raw, dirs, used);
  return b.d;
}

FarthestDiagram farthest_voronoi(const std::vector<Segment>& segments) {
  std::vector<std::vector<Point>> sites;
  sites.reserve(segments.size());
  for (const Segment& s : segments) sites.push_back({s.a, s.b});
  return farthest_voronoi(sites);
}

FarthestDiagram farthest_voronoi_l1(const std::vector<Segment>& segments) {
  std::vector<Segment> r;
  for (const Segment& s : segments)
    r.push_back({{s.a.x + s.a.y, s.a.x - s.a.y}, {s.b.x + s.b.y, s.b.x - s.b.y}});
  FarthestDiagram d = farthest_voronoi(r);
  auto back = [](Vec2& p) { p = {0.5 * (p.x + p.y), 0.5 * (p.x - p.y)}; };
  for (FarthestVertex& v : d.vertices) back(v.at);
  for (FarthestEdge& e : d.edges) {
    back(e.direction);
    e.direction = unit(e.direction.x, e.direction.y);
  }
  for (FarthestFace& f : d.faces) {
    back(f.direction);
    f.direction = unit(f.direction.x, f.direction.y);
  }
  back(d.root.p);
  back(d.root.q);
  return d;
}

double farthest_distance(const std::vector<std::vector<Point>>& sites, const Vec2& p,
                         std::vector<std::int32_t>* owners, double tol) {
  std::vector<double> ds;
  for (const auto& s : sites) {
    const std::vector<Point> h = hull_of(s);
    double d = INFINITY;
    if (h.size() == 1) d = dist_point(p.x, p.y, double(h[0].x), double(h[0].y));
    bool inside = h.size() >= 3;
    for (std::size_t i = 0; h.size() >= 2 && i < h.size(); ++i) {
      const Point& a = h[i];
      const Point& b = h[(i + 1) % h.size()];
      d = std::min(d, dist_segment(p.x, p.y, a, b));
      inside &= double(b.x - a.x) * (p.y - double(a.y)) - double(b.y - a.y) * (p.x - double(a.x)) >= 0;
      if (h.size() == 2) break;
    }
    ds.push_back(inside ? 0.0 : d);
  }
  const double m = ds.empty() ? 0 : *std::max_element(ds.begin(), ds.end());
  if (owners) {
    owners->clear();
    for (std::size_t i = 0; i < ds.size(); ++i)
      if (ds[i] >= m - tol * (1 + m)) owners->push_back(std::int32_t(i));
  }
  return m;
}

FarthestDiagram farthest_voronoi_l1(const std::vector<std::vector<Point>>& sites) {
  std::vector<Segment> segments;
  for (const auto& s : sites) {
    if (s.size() > 2) throw std::invalid_argument("the L1 diagram takes points and segments only");
    segments.push_back({s.front(), s.back()});
  }
  return farthest_voronoi_l1(segments);
}

}  // namespace linf
