#include "linf/gauges/gauge.hpp"

#include "linf/util/median.hpp"
#include "linf/util/round.hpp"
#include "util/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

namespace linf {

const char* gauge_type_name(GaugeType t) {
  switch (t) {
    case GaugeType::Internal: return "internal";
    case GaugeType::External: return "external";
    case GaugeType::Sandwich: return "sandwich";
    case GaugeType::Comb: return "comb";
    case GaugeType::T: return "T";
  }
  return "?";
}

namespace {

constexpr double kTol = 1e-7;  // DBU; clearances are exact to far better than this
constexpr double kNone = std::numeric_limits<double>::infinity();

double dot(double ax, double ay, double bx, double by) { return ax * bx + ay * by; }

// The sites that stand for a site's direction: a segment itself, or a vertex's two edges.
std::vector<std::int32_t> edges_of(const Sites& s, std::int32_t id) {
  const Site& t = s.sites[id];
  if (!t.is_point()) return {id};
  std::vector<std::int32_t> e;
  for (std::int32_t k : {t.end0, t.end1})
    if (k >= 0 && !s.sites[k].is_point()) e.push_back(k);
  return e;
}

// Two features face each other when some edge of one runs against some edge of the other at
// more than 90 degrees: across a width or a space the boundary runs both ways. This is the
// convention of KLayout's checks with ignore_angle = 90.
bool facing(const Sites& s, std::int32_t a, std::int32_t b) {
  if (s.sites[a].ring < 0 || s.sites[b].ring < 0) return false;  // plain input: no sides
  for (std::int32_t i : edges_of(s, a))
    for (std::int32_t j : edges_of(s, b)) {
      const Site& x = s.sites[i];
      const Site& y = s.sites[j];
      if (dot(double(x.b.x - x.a.x), double(x.b.y - x.a.y), double(y.b.x - y.a.x), double(y.b.y - y.a.y)) < 0)
        return true;
    }
  return false;
}

double length_of(const Site& s) { return std::hypot(double(s.b.x - s.a.x), double(s.b.y - s.a.y)); }

// The centre of the longest run of consecutive samples at the minimum value; samples are
// (position, value) in order of position, and a linear function between them.
std::pair<double, double> centre_of_minimum(const std::vector<std::pair<double, double>>& v) {
  double m = kNone;
  for (auto& x : v) m = std::min(m, x.second);
  double best_len = -1, best_pos = v.front().first;
  for (std::size_t i = 0; i < v.size();) {
    if (v[i].second > m + kTol) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < v.size() && v[j + 1].second <= m + kTol) ++j;
    const double len = v[j].first - v[i].first;
    if (len > best_len) {
      best_len = len;
      best_pos = 0.5 * (v[i].first + v[j].first);
    }
    i = j + 1;
  }
  return {best_pos, m};
}

// Arc-length samples of a stretch's clearance: where the gauge of a plain width or space goes.
Vec2 point_at_arc(const Stretch& s, double t) {
  for (std::size_t i = 0; i + 1 < s.path.size(); ++i) {
    const Vec2& a = s.path[i];
    const Vec2& b = s.path[i + 1];
    const double l = std::hypot(b.x - a.x, b.y - a.y);
    if (t <= l || i + 2 == s.path.size()) {
      const double f = l > 0 ? std::clamp(t / l, 0.0, 1.0) : 0.0;
      return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
    }
    t -= l;
  }
  return s.path.front();
}

// A stretch seen along the axis of a base edge: the clearance and the point at axis position u.
struct Along {
  Stretch s;
  std::int32_t index = -1;  // in the layer's Stretches
  double ux = 1, uy = 0;
  std::vector<double> u;  // axis position of each path point
  double lo = 0, hi = 0;

  Along(const Stretch& st, std::int32_t i, double x, double y) : s(st), index(i), ux(x), uy(y) {
    for (const Vec2& p : st.path) u.push_back(p.x * ux + p.y * uy);
    lo = *std::min_element(u.begin(), u.end());
    hi = *std::max_element(u.begin(), u.end());
  }

  // Lowest clearance where the stretch crosses position t (kNone if it does not).
  double clearance(double t, Vec2* at = nullptr) const {
    double best = kNone;
    if (u.size() == 1 && std::fabs(u[0] - t) <= kTol) {
      if (at) *at = s.path[0];
      return s.clearance[0];
    }
    for (std::size_t i = 0; i + 1 < u.size(); ++i) {
      const double a = u[i], b = u[i + 1];
      if (t < std::min(a, b) - kTol || t > std::max(a, b) + kTol) continue;
      const double f = std::fabs(b - a) > kTol ? std::clamp((t - a) / (b - a), 0.0, 1.0) : 0.0;
      double c = s.clearance[i] + f * (s.clearance[i + 1] - s.clearance[i]);
      Vec2 p{s.path[i].x + f * (s.path[i + 1].x - s.path[i].x), s.path[i].y + f * (s.path[i + 1].y - s.path[i].y)};
      if (std::fabs(b - a) <= kTol && s.clearance[i + 1] < c) {
        c = s.clearance[i + 1];
        p = s.path[i + 1];
      }
      if (c < best) {
        best = c;
        if (at) *at = p;
      }
    }
    return best;
  }
};

// min over t in the common part of `parts` of sum_k weight_k * clearance_k(t): returns
// (t at the centre of the minimum, the minimum, the common length), or a length <= 0.
struct Common {
  double t = 0, value = kNone, length = 0;
};

Common minimum_over(const std::vector<std::pair<const Along*, double>>& parts) {
  Common r;
  double lo = -kNone, hi = kNone;
  for (auto& [a, w] : parts) {
    lo = std::max(lo, a->lo);
    hi = std::min(hi, a->hi);
  }
  r.length = hi - lo;
  if (r.length <= kTol) return r;
  std::vector<double> ts{lo, hi};
  for (auto& [a, w] : parts)
    for (double t : a->u)
      if (t > lo && t < hi) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end(), [](double x, double y) { return y - x <= kTol; }), ts.end());
  std::vector<std::pair<double, double>> v;
  for (double t : ts) {
    double sum = 0;
    for (auto& [a, w] : parts) sum += w * a->clearance(t);
    if (sum < kNone) v.push_back({t, sum});
  }
  if (v.empty()) {
    r.length = 0;
    return r;
  }
  std::tie(r.t, r.value) = centre_of_minimum(v);
  return r;
}

Gauge measured(GaugeType type, const Vec2& at, double clearance, std::int32_t a,
               std::int32_t b) {
  Gauge g;
  g.type = type;
  g.at = at;
  // On a grid of 2^-20 DBU: builders round a clearance differently in its last bits, and two
  // equal widths must not become two values (the plan bins the distinct cds). Exact for the
  // integer and half-integer widths of Manhattan and 45-degree layers.
  g.cd = std::ldexp(std::nearbyint(std::ldexp(2 * clearance, 20)), -20);
  g.a = a;
  g.b = b;
  return g;
}

bool measurable(const Sites& s, std::int32_t a, std::int32_t b, PieceKind kind) {
  return kind != PieceKind::Adjacent && !adjacent(s, a, b) && facing(s, a, b);
}
bool measurable(const Sites& s, const Stretch& st) { return measurable(s, st.a, st.b, st.kind); }

double least(const Stretch& st) { return *std::min_element(st.clearance.begin(), st.clearance.end()); }

// job(i) for i in [0, n), in blocks on `threads` threads (0: one per core), for loops whose
// iterations write only their own entry: the stretches of a full layer are millions.
void in_blocks(std::size_t n, int threads, const std::function<void(std::size_t)>& job) {
  constexpr std::size_t kBlock = 4096;
  detail::parallel_for((n + kBlock - 1) / kBlock, threads, [&](unsigned, std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) job(i);
  });
}

// One gap, one gauge. In L-inf the gap between two edges continues past a corner into the
// corner vertex's bisector at the same clearance, and three sites meeting at a point give
// point stretches too. A stretch is redundant when a related stretch (each owner replaced by
// itself, its edges if a vertex, or its endpoints if an edge) that is preferred is at least as
// narrow. Preferred: a chain over a point stretch, then fewer vertex owners.
std::vector<char> redundant(const Sites& s, const Stretches& all, const std::vector<char>& ok, int threads) {
  auto vertices = [&](const Stretch& st) { return int(s.sites[st.a].is_point()) + int(s.sites[st.b].is_point()); };
  auto rank = [&](const Stretch& st) { return (st.path.size() == 1 ? 4 : 0) + vertices(st); };
  // The measurable stretches by first owner (a counting sort): a lookup scans a site's few
  // pairs. A flat index, where a map would cost more than the stretches.
  struct ByPair {
    std::int32_t b;
    std::uint32_t i;
  };
  std::vector<std::uint32_t> from(s.sites.size() + 1, 0);
  for (std::size_t i = 0; i < all.size(); ++i)
    if (ok[i]) ++from[std::size_t(all[i].a) + 1];
  for (std::size_t k = 1; k < from.size(); ++k) from[k] += from[k - 1];
  Paged<ByPair> by_pair;
  by_pair.resize(from.back());
  {
    std::vector<std::uint32_t> next(from.begin(), from.end() - 1);
    for (std::size_t i = 0; i < all.size(); ++i)
      if (ok[i]) by_pair[next[std::size_t(all[i].a)]++] = {all[i].b, std::uint32_t(i)};
  }
  auto related = [&](std::int32_t x) {  // an array, not a vector: called a few times a stretch
    const Site& t = s.sites[x];
    return std::array<std::int32_t, 3>{x, t.end0, t.end1};
  };
  // Each stretch's answer reads the others only: blocks on every core.
  std::vector<char> out(all.size(), 0);
  in_blocks(all.size(), threads, [&](std::size_t i) {
    const Stretch& st = all[i];
    if (!ok[i] || rank(st) == 0) return;
    const double c = least(st);
    for (std::int32_t x : related(st.a))
      for (std::int32_t y : related(st.b)) {
        if (x < 0 || y < 0) continue;
        const std::int32_t lo = std::min(x, y), hi = std::max(x, y);
        for (std::uint32_t k = from[std::size_t(lo)]; k < from[std::size_t(lo) + 1]; ++k) {
          if (by_pair[k].b != hi) continue;
          const Stretch other = all[by_pair[k].i];
          if (rank(other) < rank(st) && least(other) <= c + kTol) out[i] = 1;
        }
      }
  });
  return out;
}

// A width or a space: at the centre of the stretch's part of least clearance.
Gauge plain_gauge(const Stretch& st, std::int32_t index) {
  std::vector<std::pair<double, double>> v;
  double arc = 0;
  for (std::size_t i = 0; i < st.path.size(); ++i) {
    if (i) arc += std::hypot(st.path[i].x - st.path[i - 1].x, st.path[i].y - st.path[i - 1].y);
    v.push_back({arc, st.clearance[i]});
  }
  auto [t, c] = centre_of_minimum(v);
  Gauge g = measured(st.kind == PieceKind::Internal ? GaugeType::Internal : GaugeType::External,
                     point_at_arc(st, t), c, st.a, st.b);
  g.score = g.cd;
  g.tiebreak = st.length;
  g.stretch = index;
  return g;
}

// The external stretches at each site, in compressed rows.
class ExternalAt {
 public:
  void build(std::size_t sites, const Stretches& all) {
    start_.resize(sites + 1);
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Stretch s = all[i];
      if (s.kind != PieceKind::External) continue;
      ++start_[std::size_t(s.a) + 1], ++start_[std::size_t(s.b) + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    ids_.resize(start_[sites]);
    Paged<std::uint32_t> fill;
    fill.resize(sites);
    std::copy(start_.begin(), start_.end() - 1, fill.begin());
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Stretch s = all[i];
      if (s.kind != PieceKind::External) continue;
      ids_[fill[std::size_t(s.a)]++] = std::int32_t(i), ids_[fill[std::size_t(s.b)]++] = std::int32_t(i);
    }
  }
  Span<std::int32_t> of(std::int32_t site) const { return {ids_.data() + start_[site], start_[site + 1] - start_[site]}; }

 private:
  // Per site and per external stretch end: a layer's worth, in Paged arrays.
  Paged<std::uint32_t> start_;
  Paged<std::int32_t> ids_;
};

// Sandwich, comb and T gauges on one internal stretch E_y between edges a and b of a shape.
void context_gauges(const Sites& sites, const Stretches& all, std::int32_t iy, const ExternalAt& external_at,
                    const GaugeOptions& opt, std::vector<Gauge>& out) {
  const Stretch ey = all[iy];
  const Site& sa = sites.sites[ey.a];
  const double ex = double(sa.b.x - sa.a.x), ey_ = double(sa.b.y - sa.a.y);
  const double el = std::hypot(ex, ey_);
  const double ux = ex / el, uy = ey_ / el;
  const Along base(ey, iy, ux, uy);
  if (base.hi - base.lo <= kTol) return;

  std::vector<Along> side[2];
  for (int k = 0; k < 2; ++k) {
    for (std::int32_t i : external_at.of(k == 0 ? ey.a : ey.b)) {
      Along n(all[i], i, ux, uy);
      if (std::min(n.hi, base.hi) - std::max(n.lo, base.lo) > kTol) side[k].push_back(std::move(n));
    }
  }
  auto other_shape = [&](const Along& a) {
    const Site& x = sites.sites[a.s.a];
    return x.shape == sa.shape ? sites.sites[a.s.b].shape : x.shape;
  };

  // Sandwich: a neighbour on each side, all three stretches overlapping along the base.
  {
    Common best;
    std::int32_t neighbour = -1;
    for (const Along& x : side[0])
      for (const Along& z : side[1]) {
        const Common c = minimum_over({{&x, 1.0}, {&base, 2.0}, {&z, 1.0}});
        if (c.length <= kTol) continue;
        if (c.value < best.value - kTol || (c.value <= best.value + kTol && c.length > best.length + kTol)) {
          best = c;
          neighbour = (x.clearance(c.t) <= z.clearance(c.t) ? x : z).index;
        }
      }
    if (neighbour >= 0) {
      Vec2 at;
      const double cy = base.clearance(best.t, &at);
      Gauge g = measured(GaugeType::Sandwich, at, cy, ey.a, ey.b);
      g.score = 0.5 * best.value;
      g.tiebreak = best.length;
      g.stretch = iy;
      g.neighbour = neighbour;
      out.push_back(g);
    }
  }

  // Comb and T: teeth on one side: neighbours that meet the base's edge with a feature (line end,
  // narrow side, corner) at most tooth_fraction as long as that edge.
  for (int k = 0; k < 2; ++k) {
    const std::int32_t base_site = k == 0 ? ey.a : ey.b;
    Common best;
    std::int32_t tooth = -1;
    std::map<std::int32_t, bool> shapes;
    for (const Along& t : side[k]) {
      const Site& own = sites.sites[t.s.a == base_site ? t.s.b : t.s.a];
      if (length_of(own) > opt.tooth_fraction * length_of(sites.sites[base_site])) continue;
      const Common c = minimum_over({{&t, 1.0}, {&base, 1.0}});
      if (c.length <= kTol) continue;
      shapes[other_shape(t)] = true;
      if (c.value < best.value - kTol || (c.value <= best.value + kTol && c.length > best.length + kTol)) {
        best = c;
        tooth = t.index;
      }
    }
    if (tooth < 0) continue;
    Vec2 at;
    const double cy = base.clearance(best.t, &at);
    const bool comb = shapes.size() >= 2;
    Gauge g = measured(comb ? GaugeType::Comb : GaugeType::T, at, cy, ey.a, ey.b);
    g.score = (comb ? 0.75 : 0.80) * best.value;
    g.tiebreak = best.length;
    g.stretch = iy;
    g.neighbour = tooth;
    g.teeth = std::int32_t(shapes.size());
    out.push_back(g);
  }
}

// Equal scores rank by context: sandwich > comb > T > external > internal.
int context(GaugeType t) {
  switch (t) {
    case GaugeType::Sandwich: return 0;
    case GaugeType::Comb: return 1;
    case GaugeType::T: return 2;
    case GaugeType::External: return 3;
    case GaugeType::Internal: return 4;
  }
  return 5;
}

// Scores are compared on a 1e-6 DBU grid so that rounding never reorders equal widths.
long long grid(double v) { return round_half_away(v * 1e6); }

// Score, then type, longer tiebreak, place, sites; then stretch and neighbour, so that no two
// gauges tie and the order does not depend on how the sort proceeds. Key by key, each computed
// only when the ones before tie: the sort of a layer's gauges makes tens of millions of
// comparisons.
bool before(const Gauge& x, const Gauge& y) {
  if (const long long s = grid(x.score), t = grid(y.score); s != t) return s < t;
  if (const int s = context(x.type), t = context(y.type); s != t) return s < t;
  if (const long long s = grid(x.tiebreak), t = grid(y.tiebreak); s != t) return s > t;
  if (const long long s = grid(x.at.x), t = grid(y.at.x); s != t) return s < t;
  if (const long long s = grid(x.at.y), t = grid(y.at.y); s != t) return s < t;
  return std::tie(x.a, x.b, x.stretch, x.neighbour) < std::tie(y.a, y.b, y.stretch, y.neighbour);
}

// The gauges in rank order (`before`). With more than one thread, those before a pivot gauge
// (split_at_sampled_median) and the rest are sorted side by side: the order is total, so the
// result is the one sort's.
void rank_gauges(Paged<Gauge>& gauges, int threads) {
  Gauge* const first = gauges.begin();
  Gauge* const last = gauges.end();
  if (detail::worker_count(2, threads) < 2 || gauges.size() < (std::size_t(1) << 14)) {
    std::sort(first, last, before);
    return;
  }
  Gauge* const mid = detail::split_at_sampled_median(first, last, before);
  detail::parallel_for(2, threads, [&](unsigned, std::size_t k) {
    if (k == 0) std::sort(first, mid, before);
    else std::sort(mid, last, before);
  });
}

StretchFilter measurable_pairs(const Sites& s) {
  return [&s](std::int32_t a, std::int32_t b, PieceKind kind) { return measurable(s, a, b, kind); };
}

}  // namespace

bool measurable_pair(const Sites& sites, std::int32_t a, std::int32_t b, PieceKind kind) {
  return measurable(sites, a, b, kind);
}

Stretches gauge_stretches(const Diagram& d) { return stretches_of(d, measurable_pairs(d.sites)); }
Stretches take_gauge_stretches(Diagram& d) { return take_stretches(d, measurable_pairs(d.sites)); }

Gauges gauges_of(const Diagram& d, const GaugeOptions& opt) { return gauges_of(d.sites, gauge_stretches(d), opt); }

Gauges gauges_of(const Sites& sites, Stretches stretches, const GaugeOptions& opt) {
  Gauges r;
  r.stretches = std::move(stretches);
  const std::int32_t n = std::int32_t(r.stretches.size());
  std::vector<char> ok(std::size_t(n), 0);  // char, not bool: written from several threads
  in_blocks(std::size_t(n), opt.threads, [&](std::size_t i) { ok[i] = measurable(sites, r.stretches[i]); });
  const std::vector<char> extra = redundant(sites, r.stretches, ok, opt.threads);
  for (std::int32_t i = 0; i < n; ++i) ok[i] = ok[i] && !extra[i];
  // The typical width decides which spaces are pattern (see GaugeOptions::space_limit_widths).
  Paged<Weighted> widths;
  for (std::int32_t i = 0; i < n; ++i)
    if (ok[i] && r.stretches[i].kind == PieceKind::Internal) widths.push_back({2 * least(r.stretches[i]), r.stretches[i].length});
  r.typical_width = weighted_median_in_place(widths);
  widths = Paged<Weighted>();
  r.space_limit = opt.space_limit_widths > 0 && r.typical_width > 0 ? opt.space_limit_widths * r.typical_width : kNone;
  for (std::int32_t i = 0; i < n; ++i)
    if (ok[i] && r.stretches[i].kind != PieceKind::Internal && 2 * least(r.stretches[i]) > r.space_limit + kTol)
      ok[i] = false;
  // Only the stretches that make gauges or are a neighbour's from here on: the others go.
  r.measurable = std::size_t(n);
  r.stretches.keep_only(std::vector<bool>(ok.begin(), ok.end()));
  const std::int32_t m = std::int32_t(r.stretches.size());
  ExternalAt external_at;
  external_at.build(sites.sites.size(), r.stretches);
  // Room for the most there can be, reserved at once: pages are committed only as gauges are
  // written, where a vector growing by doubling would hold one and a half times them while it
  // moves (hundreds of MB on a full layer). A stretch gives one plain gauge, an internal one
  // at most a sandwich and a comb or T on each side.
  std::size_t most = 0;
  for (std::int32_t i = 0; i < m; ++i)
    most += r.stretches[i].kind == PieceKind::Internal ? 4 : 1;
  r.gauges.reserve(most);
  // Each stretch's gauges depend on it and its neighbours alone: placed in blocks on every core,
  // a round of blocks at a time, and appended in stretch order.
  constexpr std::int32_t kBlock = 4096;
  const std::int32_t blocks = (m + kBlock - 1) / kBlock;
  const std::int32_t round = std::int32_t(4 * detail::worker_count(std::size_t(blocks), opt.threads));
  std::vector<std::vector<Gauge>> placed;
  for (std::int32_t first = 0; first < blocks; first += round) {
    placed.assign(std::size_t(std::min(round, blocks - first)), {});
    detail::parallel_for(placed.size(), opt.threads, [&](unsigned, std::size_t k) {
      std::vector<Gauge>& out = placed[k];
      const std::int32_t b = first + std::int32_t(k);
      for (std::int32_t i = b * kBlock; i < std::min(m, (b + 1) * kBlock); ++i) {
        const Stretch s = r.stretches[i];
        out.push_back(plain_gauge(s, i));
        if (s.kind == PieceKind::Internal && !sites.sites[s.a].is_point() && !sites.sites[s.b].is_point())
          context_gauges(sites, r.stretches, i, external_at, opt, out);
      }
    });
    // Appended in order, each block's gauges copied to their place on the threads: on a full
    // layer the gauges are a file's pages, each faulted in as it is first written.
    std::vector<std::size_t> at(placed.size() + 1, r.gauges.size());
    for (std::size_t k = 0; k < placed.size(); ++k) at[k + 1] = at[k] + placed[k].size();
    r.gauges.grow_unwritten(at.back());
    detail::parallel_for(placed.size(), opt.threads, [&](unsigned, std::size_t k) {
      std::copy(placed[k].begin(), placed[k].end(), r.gauges.begin() + std::ptrdiff_t(at[k]));
    });
  }
  rank_gauges(r.gauges, opt.threads);
  for (const Gauge& g : r.gauges) r.top_score = std::max(r.top_score, g.score);
  return r;
}

}  // namespace linf
