#include "linf/diagram/checker.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "linf/util/box_tree.hpp"
#include "linf/geometry/distance.hpp"
#include "util/parallel.hpp"

namespace linf {

namespace {

std::int32_t down(double v) { return std::int32_t(std::max(-2147483647.0, std::min(2147483647.0, std::floor(v)))); }
std::int32_t up(double v) { return std::int32_t(std::max(-2147483647.0, std::min(2147483647.0, std::ceil(v)))); }
// Queries are widened to whole numbers: a site found by a double box is found by its integer cover.
IntBox square(double x, double y, double r) { return {down(x - r), down(y - r), up(x + r), up(y + r)}; }

// The sites in a BoxTree (a layer has millions: their index goes to file pages with them).
class SiteTree {
 public:
  explicit SiteTree(const SiteList& s)
      : s_(s), tree_(s.size(), [&s](std::size_t i) {
          const Site& t = s[i];
          return IntBox{std::int32_t(std::min(t.a.x, t.b.x)), std::int32_t(std::min(t.a.y, t.b.y)),
                        std::int32_t(std::max(t.a.x, t.b.x)), std::int32_t(std::max(t.a.y, t.b.y))};
        }) {}
  // For the points (x[i], y[i]), i < n: f(i, site, distance) for every site strictly closer
  // than r[i] to point i. One search of the index for all of them: a piece's samples are close
  // together, and the search costs more than the distances.
  template <class F>
  void closer_than(const double* x, const double* y, const double* r, std::size_t n, F&& f) const {
    IntBox q{INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN};
    for (std::size_t i = 0; i < n; ++i) {
      if (r[i] <= 0) continue;
      const IntBox b = square(x[i], y[i], r[i]);
      q = {std::min(q.x1, b.x1), std::min(q.y1, b.y1), std::max(q.x2, b.x2), std::max(q.y2, b.y2)};
    }
    if (q.x1 > q.x2) return;
    tree_.query(q, [&](std::int32_t s) {
      for (std::size_t i = 0; i < n; ++i) {
        if (r[i] <= 0) continue;
        const double d = dist_site(x[i], y[i], s_[s]);
        if (d < r[i]) f(i, s, d);
      }
    });
  }
  void k_nearest(double x, double y, unsigned k, std::vector<std::int32_t>& out) const {
    out.clear();
    tree_.nearest(x, y, [&](std::int32_t i) {
      out.push_back(i);
      return out.size() < k;
    });
  }
  // The owner of (x, y) under the ownership rule (least L-inf, then least L1, then point
  // before segment, then lower index) and its distance. `clear` is false when some other
  // site is within `tol` without tying exactly: too close to a boundary to judge.
  struct Owner { std::int32_t site = -1; double dist = INFINITY; bool clear = true; };
  // `guess`: a likely distance to the owner (> 0), where the search starts.
  Owner owner(double x, double y, double tol, double guess) const {
    // The sites whose boxes meet a square about the point holding every site within the least
    // distance found plus tol. Most points lie within `guess` of a site, and one search of
    // that square settles them (a nearest-box search cost five times more). Farther out, the
    // two nearest boxes bound the distance first: a square grown by doubling would overshoot
    // into the layout and take thousands of sites.
    std::vector<std::pair<double, std::int32_t>> c;
    Owner o;
    auto search = [&](double r) {
      c.clear();
      tree_.query(square(x, y, r), [&](std::int32_t i) { c.emplace_back(dist_site(x, y, s_[i]), i); });
      o.dist = INFINITY;
      for (const auto& e : c) o.dist = std::min(o.dist, e.first);
      return o.dist + tol + 1e-9 <= r;
    };
    if (!search(guess)) {
      double bound = o.dist;
      int guesses = 0;
      tree_.nearest(x, y, [&](std::int32_t i) {
        bound = std::min(bound, dist_site(x, y, s_[i]));
        return ++guesses < 2;
      });
      search(bound + tol + 1e-9);
    }
    // Distances tie within their rounding: a few ulps of the local lengths (differences of
    // coordinates round relative to themselves) and of the point's coordinates. Not more: a
    // site nearer by more than that is nearer, and the L1 tie-break must not decide there
    // (1e-12 of the coordinates would be 2e-3 DBU near 2^30).
    // Within that, only equal values are a tie the rule decides: two that differ by less than
    // their rounding could be either way round (a segment whose L1 distance falls below its
    // own end point's by 1e-9 at 10^8 DBU was taken for a tie), so the point is not clear.
    const double exact = 1e-12 * (1 + o.dist) + 1e-15 * (std::fabs(x) + std::fabs(y));
    double lmin = INFINITY;
    std::vector<std::pair<double, std::int32_t>> tied;
    for (const auto& e : c) {
      if (e.first <= o.dist + exact) {
        tied.emplace_back(dist_site_l1(x, y, s_[e.second]), e.second);
        if (e.first != o.dist) o.clear = false;
      } else if (e.first <= o.dist + tol) {
        o.clear = false;
      }
    }
    for (const auto& e : tied) lmin = std::min(lmin, e.first);
    for (const auto& e : tied) {
      if (e.first <= lmin + exact) {
        if (o.site < 0 || before(e.second, o.site)) o.site = e.second;
        if (e.first != lmin) o.clear = false;
      } else if (e.first <= lmin + tol) {
        o.clear = false;
      }
    }
    return o;
  }

 private:
  bool before(std::int32_t a, std::int32_t b) const {
    const bool pa = s_[a].is_point(), pb = s_[b].is_point();
    return pa != pb ? pa : a < b;
  }
  const SiteList& s_;
  BoxTree tree_;
};

// Counts a failure in `r` and keeps the first few messages.
void fail(CheckReport& r, std::size_t& counter, const std::string& msg) {
  ++counter;
  if (r.messages.size() < 20) r.messages.push_back(msg);
}

// Whether piece (a, b, p) is searched for a closer site when one piece in `every` is: a hash of
// the piece itself, so that the choice depends neither on the threads nor on the order.
bool searched(const Piece& pc, int every) {
  if (every <= 1) return true;
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  auto mix = [&h](std::uint64_t v) {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h ^= h >> 31, h *= 0xbf58476d1ce4e5b9ull, h ^= h >> 29;
  };
  std::uint64_t px, py;
  std::memcpy(&px, &pc.p.x, 8), std::memcpy(&py, &pc.p.y, 8);
  mix(std::uint32_t(pc.a)), mix(std::uint32_t(pc.b)), mix(px), mix(py);
  return h % std::uint64_t(every) == 0;
}

bool segments_cross(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  auto orient = [](const Vec2& o, const Vec2& u, const Vec2& v) {
    return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
  };
  const double d1 = orient(p, q, a), d2 = orient(p, q, b), d3 = orient(a, b, p), d4 = orient(a, b, q);
  return ((d1 <= 0 && d2 >= 0) || (d1 >= 0 && d2 <= 0)) && ((d3 <= 0 && d4 >= 0) || (d3 >= 0 && d4 <= 0));
}

}  // namespace

struct Checker::Impl {
  const SiteList& S;
  Box clip;
  CheckOptions opt;
  double tol = 0;
  SiteTree sites;
  CheckReport rep;
  struct Pair { Vec2 p, q; std::int32_t sp, sq; };
  std::vector<Pair> separated;
  // The separated pairs by their least x, and the widest pair's width: a piece meets only the
  // pairs from its least x minus that width to its greatest x (a few thousand short pairs, so
  // a sorted array does it in a binary search where a tree cost more than the test).
  std::vector<std::pair<double, std::int32_t>> by_x;
  double widest = 0;
  // The pieces crossing each pair: how many (up to 2: one is enough to judge), and the
  // owners of one of them (the least pair, so that batches and threads agree).
  struct Crossing {
    std::uint8_t n = 0;
    std::int32_t a = -1, b = -1;
    void add(std::int32_t u, std::int32_t w) {
      if (u > w) std::swap(u, w);
      if (n == 0 || std::make_pair(u, w) < std::make_pair(a, b)) a = u, b = w;
      if (n < 2) ++n;
    }
    void add(const Crossing& c) {
      if (c.n == 0) return;
      add(c.a, c.b);
      if (c.n > 1) n = 2;
    }
  };
  std::vector<Crossing> crossed;

  Impl(const SiteList& s, const Box& c, const CheckOptions& o) : S(s), clip(c), opt(o), sites(s) {}

  // Completeness: a change of owner (by the ownership rule) between two close points needs a
  // piece between them. The pairs are drawn first and indexed (a few thousand); then every
  // piece marks the pairs it crosses. An index over the pieces instead would cost more memory
  // than the pieces themselves on a large layer, and would need them all at once.
  void draw_pairs(double typical_clearance) {
    double bx1 = INFINITY, by1 = INFINITY, bx2 = -INFINITY, by2 = -INFINITY, scale = 1;
    for (const Site& t : S)
      for (const Point& p : {t.a, t.b}) {
        bx1 = std::min(bx1, double(p.x)), by1 = std::min(by1, double(p.y));
        bx2 = std::max(bx2, double(p.x)), by2 = std::max(by2, double(p.y));
        scale = std::max({scale, std::fabs(double(p.x)), std::fabs(double(p.y))});
      }
    tol = opt.tolerance > 0 ? opt.tolerance : 1e-6 + 1e-9 * scale;
    std::mt19937_64 rng(opt.seed);
    const double mx = std::max(1.0, 0.1 * std::max(bx2 - bx1, by2 - by1));
    std::uniform_real_distribution<double> ux(bx1 - mx, bx2 + mx), uy(by1 - mx, by2 + mx), ua(0, 2 * M_PI);
    std::uniform_real_distribution<double> u01(0, 1);
    // Half the pairs fall anywhere; half near a random site, within a typical clearance of it,
    // where most Voronoi edges are.
    const double reach = 2 * typical_clearance + opt.pair_step;
    std::uniform_int_distribution<std::size_t> us(0, S.size() - 1);
    for (int i = 0; i < opt.crossing_pairs; ++i) {
      Vec2 p{ux(rng), uy(rng)};
      if (i % 4 == 1) {
        const Site& t = S[us(rng)];
        const double f = u01(rng);
        p = {double(t.a.x) + f * double(t.b.x - t.a.x) + reach * (2 * u01(rng) - 1),
             double(t.a.y) + f * double(t.b.y - t.a.y) + reach * (2 * u01(rng) - 1)};
      } else if (i % 4 == 3) {
        // Halfway between a site and one of its neighbours: right where their edge should be.
        const Site& t = S[us(rng)];
        const double f = u01(rng);
        const Vec2 pt{double(t.a.x) + f * double(t.b.x - t.a.x), double(t.a.y) + f * double(t.b.y - t.a.y)};
        std::vector<std::int32_t> near;
        sites.k_nearest(pt.x, pt.y, 8, near);
        const Site& u = S[near[std::size_t(u01(rng) * double(near.size())) % near.size()]];
        const double g = u01(rng);
        const Vec2 pu{double(u.a.x) + g * double(u.b.x - u.a.x), double(u.a.y) + g * double(u.b.y - u.a.y)};
        p = {0.5 * (pt.x + pu.x) + opt.pair_step * (2 * u01(rng) - 1), 0.5 * (pt.y + pu.y) + opt.pair_step * (2 * u01(rng) - 1)};
      }
      const double ang = ua(rng);
      const Vec2 q{p.x + opt.pair_step * std::cos(ang), p.y + opt.pair_step * std::sin(ang)};
      auto inside = [&](const Vec2& v) { return v.x > clip.x1 && v.x < clip.x2 && v.y > clip.y1 && v.y < clip.y2; };
      if (!inside(p) || !inside(q)) continue;  // the diagram ends at the clip box
      const double guess = std::max(1.0, typical_clearance);
      const auto op = sites.owner(p.x, p.y, tol, guess), oq = sites.owner(q.x, q.y, tol, guess);
      ++rep.pairs_tested;
      if (!op.clear || !oq.clear || op.site == oq.site) continue;
      if (op.dist <= tol || oq.dist <= tol) continue;  // on the boundary itself: no edge needed there
      ++rep.pairs_separated;
      separated.push_back({p, q, op.site, oq.site});
    }
    for (std::size_t i = 0; i < separated.size(); ++i) {
      const Pair& x = separated[i];
      by_x.emplace_back(std::min(x.p.x, x.q.x), std::int32_t(i));
      widest = std::max(widest, std::fabs(x.p.x - x.q.x));
    }
    std::sort(by_x.begin(), by_x.end());
    crossed.assign(separated.size(), Crossing{});
  }

  // Every piece sampled at its ends and inside, and the pairs it crosses marked. Chunks of
  // pieces on the worker threads, each into its own report and marks, merged in chunk order,
  // so that the messages do not depend on the threads.
  void add(const Piece* pieces, std::size_t n) {
    const int k = std::clamp(opt.samples_per_piece, 2, kMostSamples);
    const std::size_t chunk = 4096, nchunks = (n + chunk - 1) / chunk;
    std::vector<CheckReport> part(nchunks);
    std::vector<std::vector<Crossing>> marks(detail::worker_count(nchunks, opt.threads), std::vector<Crossing>(separated.size()));
    auto sample = [&](unsigned w, std::size_t c) {
      CheckReport& r = part[c];
      for (std::size_t pi = c * chunk; pi < std::min(n, (c + 1) * chunk); ++pi) {
        const Piece& pc = pieces[pi];
        const Site &sa = S[pc.a], &sb = S[pc.b];
        // Plain arrays: the samples of a few hundred thousand pieces a second, where vectors'
        // set-up cost more than the distances.
        std::array<double, kMostSamples> xs, ys, da, db, radius;
        for (int i = 0; i < k; ++i) {
          const double t = double(i) / double(k - 1);
          xs[i] = pc.p.x + t * (pc.q.x - pc.p.x), ys[i] = pc.p.y + t * (pc.q.y - pc.p.y);
          da[i] = dist_site(xs[i], ys[i], sa), db[i] = dist_site(xs[i], ys[i], sb);
          radius[i] = std::min(da[i], db[i]) - tol;
        }
        auto where = [&](int i) {  // formatted on failure only: sampling runs by the million
          std::ostringstream w;
          w.precision(12);
          w << "(" << xs[i] << "," << ys[i] << ") owners " << pc.a << "," << pc.b << " da=" << da[i] << " db=" << db[i];
          return w.str();
        };
        for (int i = 0; i < k; ++i) {
          ++r.sampled_points;
          r.worst_error = std::max(r.worst_error, std::fabs(da[i] - db[i]));
          if (std::fabs(da[i] - db[i]) > tol) fail(r, r.equidistance_errors, "not equidistant at " + where(i));
          if (i == 0 || i == k - 1) {
            const double stated = i == 0 ? pc.d1 : pc.d2;
            r.worst_error = std::max(r.worst_error, std::fabs(stated - da[i]));
            if (std::fabs(stated - da[i]) > tol) fail(r, r.clearance_errors, "wrong clearance at " + where(i));
          }
        }
        // The nearest site closer than the owners, at each sample (of the pieces searched).
        if (searched(pc, opt.search_every)) {
          ++r.searched_pieces;
          std::array<std::int32_t, kMostSamples> closer;
          std::array<double, kMostSamples> dc;
          closer.fill(-1), dc.fill(INFINITY);
          sites.closer_than(xs.data(), ys.data(), radius.data(), std::size_t(k), [&](std::size_t i, std::int32_t s, double d) {
            if (d < dc[i]) closer[i] = s, dc[i] = d;
          });
          for (int i = 0; i < k; ++i) {
            if (closer[i] < 0) continue;
            r.worst_error = std::max(r.worst_error, radius[i] + tol - dc[i]);
            std::ostringstream m;
            m << "site " << closer[i] << " at " << dc[i] << " is closer than the owners at " << where(i);
            fail(r, r.closer_site_errors, m.str());
          }
        }
        const double x1 = std::min(pc.p.x, pc.q.x), x2 = std::max(pc.p.x, pc.q.x);
        const double y1 = std::min(pc.p.y, pc.q.y), y2 = std::max(pc.p.y, pc.q.y);
        auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(x1 - widest, INT32_MIN));
        for (; it != by_x.end() && it->first <= x2; ++it) {
          const Pair& x = separated[std::size_t(it->second)];
          if (std::max(x.p.y, x.q.y) < y1 || std::min(x.p.y, x.q.y) > y2) continue;
          if (segments_cross(x.p, x.q, pc.p, pc.q)) marks[w][std::size_t(it->second)].add(pc.a, pc.b);
        }
      }
    };
    detail::parallel_for(nchunks, opt.threads, sample);
    for (const CheckReport& r : part) {
      rep.sampled_points += r.sampled_points;
      rep.searched_pieces += r.searched_pieces;
      rep.worst_error = std::max(rep.worst_error, r.worst_error);
      rep.equidistance_errors += r.equidistance_errors;
      rep.clearance_errors += r.clearance_errors;
      rep.closer_site_errors += r.closer_site_errors;
      for (const std::string& m : r.messages)
        if (rep.messages.size() < 20) rep.messages.push_back(m);
    }
    for (const std::vector<Crossing>& m : marks)
      for (std::size_t i = 0; i < m.size(); ++i) crossed[i].add(m[i]);
  }

  CheckReport finish() {
    for (std::size_t i = 0; i < separated.size(); ++i) {
      const Crossing& c = crossed[i];
      const Pair& x = separated[i];
      if (c.n == 2 || (c.n == 1 && std::min(x.sp, x.sq) == c.a && std::max(x.sp, x.sq) == c.b)) continue;
      std::ostringstream m;
      m.precision(12);
      m << (c.n == 0 ? "no piece" : "only a piece of " + std::to_string(c.a) + "," + std::to_string(c.b)) << " between ("
        << x.p.x << "," << x.p.y << ") nearest " << x.sp << " and (" << x.q.x << "," << x.q.y << ") nearest " << x.sq;
      fail(rep, c.n == 0 ? rep.missing_edge_errors : rep.wrong_owner_errors, m.str());
    }
    return rep;
  }
};

Checker::Checker(const Sites& sites, const Box& clip, double typical_clearance, const CheckOptions& opt) {
  if (sites.sites.empty()) return;
  impl_ = std::make_unique<Impl>(sites.sites, clip, opt);
  impl_->draw_pairs(typical_clearance);
}

Checker::~Checker() = default;

void Checker::add(const Piece* pieces, std::size_t n) {
  if (impl_ && n) impl_->add(pieces, n);
}

CheckReport Checker::finish() { return impl_ ? impl_->finish() : CheckReport{}; }

double median_clearance(std::vector<double> sample) {
  if (sample.empty()) return 1.0;
  std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
  return sample[sample.size() / 2];
}

double typical_clearance(const std::vector<Piece>& pieces) {
  std::vector<double> clear;
  for (std::size_t i = 0; i < pieces.size(); i += 1 + pieces.size() / 1000) clear.push_back(pieces[i].d1);
  return median_clearance(std::move(clear));
}

CheckReport check_diagram(const Diagram& d, const CheckOptions& opt) {
  Checker c(d.sites, d.clip, typical_clearance(d.pieces), opt);
  c.add(d.pieces.data(), d.pieces.size());
  return c.finish();
}

}  // namespace linf
