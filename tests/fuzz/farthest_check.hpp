// The farthest-site diagram against brute force (farthest_distance): the checks of
// tests/cpp/farthest/test_farthest.cpp without GoogleTest, plus regions and the root, trusting
// the faces' geometry no further than their vertices and edges:
//   vertices  at their weight, every face meeting there owned by sites farthest there;
//   edges     points along every edge and ray farthest from the owners of both its faces (and
//             along an edge at the weight between its ends: the distance is affine there);
//   regions   random points near the sites and far out: the edge or vertex nearest to a point
//             borders the face that holds it, so one of the faces there must be owned by sites
//             farthest at the point. A wrong owner or a missing region fails here;
//   root      its half-side is the farthest distance at its ends and the least anywhere.
// Tolerances grow with the distances and with the coordinates' magnitude (doubles near 2^30).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "linf/farthest/farthest.hpp"

namespace linf::fuzz {

class FarthestCheck {
 public:
  FarthestCheck(const std::vector<std::vector<Point>>& sites, const FarthestDiagram& d) : sites_(sites), d_(d) {
    bool first = true;
    for (const auto& s : sites)
      for (const Point& q : s) {
        const double x = double(q.x), y = double(q.y);
        if (first) x1_ = x2_ = x, y1_ = y2_ = y, first = false;
        x1_ = std::min(x1_, x), x2_ = std::max(x2_, x), y1_ = std::min(y1_, y), y2_ = std::max(y2_, y);
        magnitude_ = std::max({magnitude_, std::fabs(x), std::fabs(y)});
      }
    extent_ = std::max({1.0, x2_ - x1_, y2_ - y1_});
  }

  // The first failure, or an empty string.
  std::string run(std::uint64_t seed) {
    if (sites_.empty()) return d_.faces.empty() ? "" : "faces without sites";
    if (std::string e = structure(); !e.empty()) return e;
    for (std::size_t v = 0; v < d_.vertices.size(); ++v) {
      const FarthestVertex& x = d_.vertices[v];
      const double f = farthest_distance(sites_, x.at);
      if (!near(f, x.weight, x.at))
        return say("vertex %zu at (%.17g, %.17g): weight %.17g, farthest distance %.17g", v, x.at.x, x.at.y, x.weight, f);
      if (!farthest_owners(x.at, x.faces, true))
        return say("vertex %zu at (%.17g, %.17g): the owners of its faces are not all farthest", v, x.at.x, x.at.y);
    }
    for (std::size_t k = 0; k < d_.edges.size(); ++k) {
      const FarthestEdge& e = d_.edges[k];
      const FarthestVertex& a = d_.vertices[e.from];
      for (double t : {0.25, 0.5, 0.75}) {
        Vec2 p;
        double w = -1;
        if (e.to >= 0) {
          const FarthestVertex& b = d_.vertices[e.to];
          p = {a.at.x + t * (b.at.x - a.at.x), a.at.y + t * (b.at.y - a.at.y)};
          w = a.weight + t * (b.weight - a.weight);
        } else {
          const double r = std::pow(100.0, 4 * t - 2) * extent_;  // 0.01, 1 and 100 extents out
          p = {a.at.x + r * e.direction.x, a.at.y + r * e.direction.y};
        }
        const double f = farthest_distance(sites_, p);
        if (w >= 0 && !near(f, w, p))
          return say("edge %zu at (%.17g, %.17g): weight %.17g between its ends, farthest distance %.17g", k, p.x,
                     p.y, w, f);
        if (!farthest_owners(p, {e.left, e.right}, true))
          return say("edge %zu at (%.17g, %.17g): the owners of faces %d and %d are not both farthest", k, p.x, p.y,
                     e.left, e.right);
      }
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    const double cx = 0.5 * (x1_ + x2_), cy = 0.5 * (y1_ + y2_);
    for (int k = 0; k < 40; ++k) {
      Vec2 p;
      if (k < 32) {
        p = {x1_ - extent_ + U(rng) * (x2_ - x1_ + 2 * extent_), y1_ - extent_ + U(rng) * (y2_ - y1_ + 2 * extent_)};
      } else {
        const double angle = 2 * M_PI * U(rng), r = 100 * extent_;
        p = {cx + r * std::cos(angle), cy + r * std::sin(angle)};
      }
      const double f = farthest_distance(sites_, p);
      if (f < d_.root.half_side && !near(f, d_.root.half_side, p))
        return say("(%.17g, %.17g): farthest distance %.17g below the root's half-side %.17g", p.x, p.y, f,
                   d_.root.half_side);
      if (!farthest_owners(p, faces_beside(p), false))
        return say("(%.17g, %.17g): no face beside it is owned by its farthest sites", p.x, p.y);
    }
    for (const Vec2& c : {d_.root.p, d_.root.q}) {
      const double f = farthest_distance(sites_, c);
      if (!near(f, d_.root.half_side, c))
        return say("root end (%.17g, %.17g): farthest distance %.17g, half-side %.17g", c.x, c.y, f, d_.root.half_side);
    }
    return "";
  }

 private:
  const std::vector<std::vector<Point>>& sites_;
  const FarthestDiagram& d_;
  double x1_ = 0, y1_ = 0, x2_ = 0, y2_ = 0, extent_ = 1, magnitude_ = 0;

  template <class... A>
  static std::string say(const char* format, A... a) {
    char line[512];
    std::snprintf(line, sizeof line, format, a...);
    return line;
  }

  double magnitude(const Vec2& p) const { return std::max({magnitude_, std::fabs(p.x), std::fabs(p.y)}); }

  // Rounding: of the distance, and of points at this magnitude.
  double tolerance(const Vec2& p, double distance) const { return 1e-9 * (1 + distance) + 1e-12 * magnitude(p); }

  bool near(double f, double w, const Vec2& p) const { return std::fabs(f - w) <= tolerance(p, f); }

  // The owners of all (or, !all, of some) of `faces` are among the farthest sites at p.
  bool farthest_owners(const Vec2& p, const std::vector<std::int32_t>& faces, bool all) const {
    const double f = farthest_distance(sites_, p);
    std::vector<std::int32_t> own;
    auto owned = [&](std::int32_t face) {
      const auto& o = d_.faces[face].owners;
      return std::all_of(o.begin(), o.end(),
                         [&](std::int32_t s) { return std::find(own.begin(), own.end(), s) != own.end(); });
    };
    farthest_distance(sites_, p, &own, tolerance(p, f) / (1 + f));
    return all ? std::all_of(faces.begin(), faces.end(), owned) : std::any_of(faces.begin(), faces.end(), owned);
  }

  // Indices in range, every face owned, rays of unit direction.
  std::string structure() const {
    const std::int32_t F = std::int32_t(d_.faces.size()), V = std::int32_t(d_.vertices.size());
    if (F == 0) return "no faces";
    for (std::int32_t f = 0; f < F; ++f) {
      if (d_.faces[f].owners.empty()) return say("face %d has no owner", f);
      for (std::int32_t s : d_.faces[f].owners)
        if (s < 0 || s >= std::int32_t(sites_.size())) return say("face %d: owner %d out of range", f, s);
    }
    for (std::int32_t v = 0; v < V; ++v)
      for (std::int32_t f : d_.vertices[v].faces)
        if (f < 0 || f >= F) return say("vertex %d: face %d out of range", v, f);
    for (std::size_t k = 0; k < d_.edges.size(); ++k) {
      const FarthestEdge& e = d_.edges[k];
      if (e.left < 0 || e.left >= F || e.right < 0 || e.right >= F || e.from < 0 || e.from >= V || e.to < -1 ||
          e.to >= V)
        return say("edge %zu: a face or vertex out of range", k);
      if (e.to < 0 && std::fabs(std::hypot(e.direction.x, e.direction.y) - 1) > 1e-9)
        return say("edge %zu: a ray of direction (%g, %g)", k, e.direction.x, e.direction.y);
    }
    if (F > 1 && d_.edges.empty()) return say("%d faces and no edge", F);
    return "";
  }

  // The faces of the edge (or vertex) nearest to p; every face when there is no edge.
  std::vector<std::int32_t> faces_beside(const Vec2& p) const {
    std::vector<std::int32_t> out;
    if (d_.edges.empty()) {
      for (std::int32_t f = 0; f < std::int32_t(d_.faces.size()); ++f) out.push_back(f);
      return out;
    }
    double best = INFINITY;
    std::size_t nearest = 0;
    int end = -1;  // the nearest point is at the edge's start (0), end (1), or inside (-1)
    for (std::size_t k = 0; k < d_.edges.size(); ++k) {
      const FarthestEdge& e = d_.edges[k];
      const Vec2 a = d_.vertices[e.from].at;
      const Vec2 u = e.to >= 0 ? Vec2{d_.vertices[e.to].at.x - a.x, d_.vertices[e.to].at.y - a.y} : e.direction;
      const double uu = u.x * u.x + u.y * u.y;
      double t = uu > 0 ? ((p.x - a.x) * u.x + (p.y - a.y) * u.y) / uu : 0;
      t = std::max(0.0, e.to >= 0 ? std::min(1.0, t) : t);
      const double dist = std::hypot(p.x - a.x - t * u.x, p.y - a.y - t * u.y);
      if (dist < best) best = dist, nearest = k, end = t <= 0 ? 0 : (e.to >= 0 && t >= 1) ? 1 : -1;
    }
    const FarthestEdge& e = d_.edges[nearest];
    out = {e.left, e.right};
    if (end >= 0) {
      const auto& more = d_.vertices[end == 0 ? e.from : e.to].faces;
      out.insert(out.end(), more.begin(), more.end());
    }
    return out;
  }
};

}  // namespace linf::fuzz
