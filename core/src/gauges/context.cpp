// Context ids (context.hpp). Everything is done in doubled coordinates relative to the point,
// (2x - 2cx, 2y - 2cy), so that a point at a half DBU is an integer and the window's sides
// lie at -2r and 2r. The clipped geometry is described by its boundary: the layer's edges
// inside the window, each directed with the layer on its left, and the parts of the window's
// own sides that lie in the layer. That set of directed segments depends on the region alone
// (not on where a ring starts nor on how a clipper walks), so a sum of its segments' hashes names it.
// Edges are cut where they cross the window's sides: an any-angle edge crosses at a rational
// point, kept exactly as a reduced fraction.
#include "linf/gauges/context.hpp"
#include "linf/util/round.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <unordered_map>

#include "util/parallel.hpp"

namespace linf {

namespace {

using I128 = __int128;

// A reduced fraction p / q, q > 0: one representation per number, so equal numbers encode alike.
struct Q {
  std::int64_t p = 0, q = 1;
  friend bool operator==(const Q& a, const Q& b) { return a.p == b.p && a.q == b.q; }
};

I128 abs128(I128 v) { return v < 0 ? -v : v; }

I128 gcd128(I128 a, I128 b) {
  a = abs128(a), b = abs128(b);
  while (b != 0) {
    const I128 t = a % b;
    a = b, b = t;
  }
  return a;
}

Q reduced(I128 n, I128 d) {  // d > 0
  if (d != 1) {
    const I128 g = gcd128(n, d);
    if (g > 1) n /= g, d /= g;
  }
  return {std::int64_t(n), std::int64_t(d)};
}

Q neg(const Q& a) { return {-a.p, a.q}; }

// a / b < c / d for b, d > 0; the terms stay below 2^35, their products below 2^70.
bool less(I128 a, I128 b, I128 c, I128 d) { return a * d < c * b; }

struct P {
  std::int64_t x, y;
};

// A directed segment of the clipped region's boundary, the region on its left.
struct Seg {
  Q x1, y1, x2, y2;
};
using Code = std::array<std::int64_t, 8>;

Code code_of(const Seg& s) { return {s.x1.p, s.x1.q, s.y1.p, s.y1.q, s.x2.p, s.x2.q, s.y2.p, s.y2.q}; }

// The quarter turn that brings side k of the window to the bottom (k = 0 bottom, 1 right, 2 top,
// 3 left), walking each side counter-clockwise as increasing x; and back.
P to_bottom(int k, P v) {
  switch (k) {
    case 1: return {v.y, -v.x};
    case 2: return {-v.x, -v.y};
    case 3: return {-v.y, v.x};
    default: return v;
  }
}

// Point u along side k (at the bottom: (u, -R)) in window coordinates.
std::pair<Q, Q> from_bottom(int k, const Q& u, std::int64_t R) {
  const Q r{R, 1}, mr{-R, 1};
  switch (k) {
    case 1: return {r, u};
    case 2: return {neg(u), r};
    case 3: return {mr, neg(u)};
    default: return {u, mr};
  }
}

// Where the layer crosses one side of the window, seen from just inside it: the side brought to
// the bottom, the line y = -R + epsilon, positions within [-R, R] and the parity left of -R.
struct Crossing {
  I128 n, d;  // x = n / d, d > 0
};
struct Side {
  std::vector<Crossing> at;
  bool odd_before = false;
};

class Window {
 public:
  explicit Window(std::int64_t R) : R_(R) {}

  void clear() {
    segs_.clear();
    for (Side& s : sides_) s.at.clear(), s.odd_before = false;
  }

  // An edge relative to the point, the layer on its left.
  void edge(P a, P b) {
    clip(a, b);
    for (int k = 0; k < 4; ++k) cross(k, to_bottom(k, a), to_bottom(k, b));
  }

  // The boundary's segments: the edges' pieces inside, then the sides' parts in the layer.
  const std::vector<Seg>& segments() {
    for (int k = 0; k < 4; ++k) side_segments(k);
    return segs_;
  }

 private:
  // The piece of a -> b in the closed window, unless it lies along a side (the sides' part in
  // the layer is found from inside, by cross(), once for all polygons).
  void clip(P a, P b) {
    if (std::max(a.x, b.x) < -R_ || std::min(a.x, b.x) > R_ || std::max(a.y, b.y) < -R_ || std::min(a.y, b.y) > R_) return;
    const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
    if (dx == 0 || dy == 0) {  // axis-parallel: the same ends as below, without fractions
      if (dx == 0 && dy == 0) return;
      if ((dx == 0 && (a.x == -R_ || a.x == R_)) || (dy == 0 && (a.y == -R_ || a.y == R_))) return;
      auto in = [&](std::int64_t v) { return Q{std::clamp(v, -R_, R_), 1}; };
      if (dy == 0) {
        if (std::min(a.x, b.x) >= R_ || std::max(a.x, b.x) <= -R_) return;  // one point at most
        segs_.push_back({in(a.x), Q{a.y, 1}, in(b.x), Q{a.y, 1}});
      } else {
        if (std::min(a.y, b.y) >= R_ || std::max(a.y, b.y) <= -R_) return;
        segs_.push_back({Q{a.x, 1}, in(a.y), Q{a.x, 1}, in(b.y)});
      }
      return;
    }
    I128 tin_n = 0, tin_d = 1, tout_n = 1, tout_d = 1;
    auto limit = [&](std::int64_t a0, std::int64_t d) {
      if (d == 0) return -R_ <= a0 && a0 <= R_;
      I128 n1 = I128(-R_) - a0, n2 = I128(R_) - a0, den = d;
      if (den < 0) n1 = -n1, n2 = -n2, den = -den;
      if (n1 > n2) std::swap(n1, n2);
      if (less(tin_n, tin_d, n1, den)) tin_n = n1, tin_d = den;
      if (less(n2, den, tout_n, tout_d)) tout_n = n2, tout_d = den;
      return true;
    };
    if (!limit(a.x, dx) || !limit(a.y, dy)) return;
    if (!less(tin_n, tin_d, tout_n, tout_d)) return;  // outside, or one point
    if ((dx == 0 && (a.x == -R_ || a.x == R_)) || (dy == 0 && (a.y == -R_ || a.y == R_))) return;
    auto at = [&](I128 n, I128 d) {
      return std::pair<Q, Q>{reduced(I128(a.x) * d + I128(dx) * n, d), reduced(I128(a.y) * d + I128(dy) * n, d)};
    };
    const auto [x1, y1] = at(tin_n, tin_d);
    const auto [x2, y2] = at(tout_n, tout_d);
    segs_.push_back({x1, y1, x2, y2});
  }

  // Whether a -> b (side k at the bottom) crosses y = -R + epsilon, and where.
  void cross(int k, P a, P b) {
    const std::int64_t y = -R_;
    if (!((a.y <= y && b.y > y) || (b.y <= y && a.y > y))) return;
    I128 d = I128(b.y) - a.y, n = I128(a.x) * d + (I128(y) - a.y) * (I128(b.x) - a.x);
    if (d < 0) n = -n, d = -d;
    Side& s = sides_[std::size_t(k)];
    if (n < I128(-R_) * d) s.odd_before = !s.odd_before;
    else if (n <= I128(R_) * d) s.at.push_back({n, d});
  }

  // The parts of side k in the layer, counter-clockwise around the window (the layer inside is
  // on their left), by parity along the side.
  void side_segments(int k) {
    Side& s = sides_[std::size_t(k)];
    std::sort(s.at.begin(), s.at.end(), [](const Crossing& p, const Crossing& q) { return less(p.n, p.d, q.n, q.d); });
    bool odd = s.odd_before;
    I128 open_n = -R_, open_d = 1;
    auto emit = [&](I128 n1, I128 d1, I128 n2, I128 d2) {
      if (!less(n1, d1, n2, d2)) return;
      const auto [x1, y1] = from_bottom(k, reduced(n1, d1), R_);
      const auto [x2, y2] = from_bottom(k, reduced(n2, d2), R_);
      segs_.push_back({x1, y1, x2, y2});
    };
    for (std::size_t i = 0; i < s.at.size();) {
      std::size_t j = i;
      bool now = odd;
      while (j < s.at.size() && !less(s.at[i].n, s.at[i].d, s.at[j].n, s.at[j].d)) now = !now, ++j;
      if (!odd && now) open_n = s.at[i].n, open_d = s.at[i].d;
      if (odd && !now) emit(open_n, open_d, s.at[i].n, s.at[i].d);
      odd = now, i = j;
    }
    if (odd) emit(open_n, open_d, R_, 1);
  }

  std::int64_t R_;
  std::vector<Seg> segs_;
  std::array<Side, 4> sides_;
};

// Drops repeated points and points in the middle of a straight run: the same region drawn with
// more vertices has the same boundary.
bool redundant(const P& p, const P& c, const P& q) {
  const I128 ux = I128(c.x) - p.x, uy = I128(c.y) - p.y, wx = I128(q.x) - c.x, wy = I128(q.y) - c.y;
  return (ux == 0 && uy == 0) || (ux * wy - uy * wx == 0 && ux * wx + uy * wy > 0);
}

void simplify(std::vector<P>& v, std::vector<P>& out) {
  for (bool changed = true; changed && v.size() >= 3;) {
    changed = false;
    out.clear();
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (redundant(v[(i + n - 1) % n], v[i], v[(i + 1) % n])) changed = true;
      else out.push_back(v[i]);
    }
    if (changed) v.swap(out);
  }
}

I128 twice_area(const std::vector<P>& v) {
  I128 a = 0;
  for (std::size_t i = 0, n = v.size(); i < n; ++i) {
    const P& p = v[i];
    const P& q = v[(i + 1) % n];
    a += I128(p.x) * q.y - I128(q.x) * p.y;
  }
  return a;
}

// A 64-bit hash of a sequence of integers, a word at a time (xxHash64's round and final mix:
// every input bit reaches every output bit), in integer arithmetic: the same on every machine.
struct Hash {
  static constexpr std::uint64_t P1 = 11400714785074694791ull, P2 = 14029467366897019727ull,
                                 P3 = 1609587929392839161ull;
  std::uint64_t h = P3;
  static std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
  void add(std::int64_t v) {
    const std::uint64_t k = rotl(std::uint64_t(v) * P2, 31) * P1;
    h = rotl(h ^ k, 27) * P1 + P3;
  }
  std::uint64_t value() const {
    std::uint64_t x = h;
    x ^= x >> 33, x *= P2, x ^= x >> 29, x *= P3, x ^= x >> 32;
    return x;
  }
};

std::int64_t neg(std::int64_t v) { return -v; }

// Segment (x1, y1) -> (x2, y2) under symmetry t of the square, in place: a swap of the axes and
// a sign for each; a mirror also reverses the segment, so that the region stays on its left.
template <typename T>
void apply_symmetry(int t, T& x1, T& y1, T& x2, T& y2) {
  const bool swap = t & 1, negx = t & 2, negy = t & 4;
  if (swap) std::swap(x1, y1), std::swap(x2, y2);
  if (negx) x1 = neg(x1), x2 = neg(x2);
  if (negy) y1 = neg(y1), y2 = neg(y2);
  if ((int(swap) + int(negx) + int(negy)) % 2 == 1) std::swap(x1, x2), std::swap(y1, y2);
}

// A segment under symmetry t, as its eight integers.
Code code_of(const Seg& s, int t) {
  Seg m = s;
  apply_symmetry(t, m.x1, m.y1, m.x2, m.y2);
  return code_of(m);
}

// MurmurHash3's 64-bit finaliser: a bijection in which every input bit reaches every output bit.
std::uint64_t fmix(std::uint64_t x) {
  x ^= x >> 33, x *= 0xff51afd7ed558ccdull, x ^= x >> 33, x *= 0xc4ceb9fe1a85ec53ull, x ^= x >> 33;
  return x;
}

std::uint64_t mixed(const std::int64_t* v, int n) {
  Hash h;
  for (int i = 0; i < n; ++i) h.add(v[i]);
  return h.value();
}

// Adds a segment's hash under each of the 8 symmetries to its sum: from its ends' four integers
// when it has integer ends (every segment of a Manhattan or 45-degree layer), else from its eight
// integers, fully mixed either way.
void hashes_of(const Seg& s, std::array<std::uint64_t, 8>& sums) {
  if (s.x1.q == 1 && s.y1.q == 1 && s.x2.q == 1 && s.y2.q == 1) {
    // The ends' coordinates are below 2^29 in size: 32 bits each, two to a word; the two words
    // combined through an odd multiplier and mixed (one finaliser a segment and symmetry).
    auto u = [](std::int64_t v) { return std::uint64_t(std::uint32_t(v + (std::int64_t(1) << 30))); };
    for (int t = 0; t < 8; ++t) {
      std::int64_t x1 = s.x1.p, y1 = s.y1.p, x2 = s.x2.p, y2 = s.y2.p;
      apply_symmetry(t, x1, y1, x2, y2);
      sums[std::size_t(t)] += fmix((u(x1) << 32 | u(y1)) + (u(x2) << 32 | u(y2)) * 0x9E3779B97F4A7C15ull);
    }
    return;
  }
  for (int t = 0; t < 8; ++t) {
    const Code c = code_of(s, t);
    sums[std::size_t(t)] += mixed(c.data(), 8);
  }
}

// The context's id: for each symmetry the sum (mod 2^64) of its segments' hashes, which no
// order of the segments changes, so nothing is sorted; the least of the 8 sums is the same for
// every symmetric image of the neighbourhood. Hashed with R and the number of segments.
std::uint64_t canonical_id(const std::vector<Seg>& segs, std::int64_t R) {
  std::array<std::uint64_t, 8> sums{};
  for (const Seg& s : segs) hashes_of(s, sums);
  Hash f;
  f.add(R);
  f.add(std::int64_t(segs.size()));
  f.add(std::int64_t(*std::min_element(sums.begin(), sums.end())));
  return f.value();
}

std::int64_t half_units(double v) {
  if (!(std::fabs(v) < double(kCoordLimit))) throw std::invalid_argument("context point outside +-2^30 DBU");
  return round_half_away(2.0 * v);
}

std::int32_t floor_half(std::int64_t v) { return std::int32_t(v >= 0 ? v / 2 : -((-v + 1) / 2)); }

}  // namespace

std::uint64_t empty_context_id(std::int64_t radius) {
  return canonical_id({}, 2 * radius);
}

// The layer's rings as the windows read them: each with its repeated points and the middles of
// straight runs dropped and oriented with the layer on its left, which neither translation nor
// doubling changes, so it is done once a ring, not once a gauge. Most rings are clean and read
// in place, forwards or backwards; the others are kept simplified.
class PreparedRings {
 public:
  PreparedRings(const PolygonIndex& layer, int threads) : layer_(layer), first_(layer.size() + 1, 0) {
    for (std::size_t p = 0; p < layer.size(); ++p) {
      std::size_t n = 0;
      layer.rings(p, [&](const std::int64_t*, std::size_t, bool) { ++n; });
      first_[p + 1] = first_[p] + n;
    }
    how_.resize(first_.back());
    std::mutex m;
    detail::parallel_for(layer.size(), threads, [&](unsigned, std::size_t p) {
      std::vector<P> v, spare;
      std::size_t k = first_[p];
      layer.rings(p, [&](const std::int64_t* xy, std::size_t n, bool outer) {
        v.resize(n);
        for (std::size_t j = 0; j < n; ++j) v[j] = {xy[2 * j], xy[2 * j + 1]};
        simplify(v, spare);
        const I128 a = v.size() < 3 ? 0 : twice_area(v);
        if (a == 0) {
          how_[k] = Skip;
        } else if (v.size() == n) {
          how_[k] = (a > 0) == outer ? Forward : Backward;
        } else {
          if ((a > 0) != outer) std::reverse(v.begin(), v.end());
          how_[k] = Copied;
          std::lock_guard<std::mutex> lock(m);
          copies_[k] = v;
        }
        ++k;
      });
    });
  }

  // The edges of polygon p's rings, relative to c (doubled units), to win.
  void edges(std::size_t p, std::int64_t cx, std::int64_t cy, Window& win) const {
    std::size_t k = first_[p];
    layer_.rings(p, [&](const std::int64_t* xy, std::size_t n, bool) {
      // The closed ring of m points, point(i) the i-th in walking order, relative to c.
      auto walk = [&](std::size_t m, auto point) {
        P a = point(m - 1);
        a = {2 * a.x - cx, 2 * a.y - cy};
        for (std::size_t i = 0; i < m; ++i) {
          const P q = point(i), b{2 * q.x - cx, 2 * q.y - cy};
          win.edge(a, b);
          a = b;
        }
      };
      const How how = how_[k];
      if (how == Forward) walk(n, [&](std::size_t i) { return P{xy[2 * i], xy[2 * i + 1]}; });
      else if (how == Backward) walk(n, [&](std::size_t i) { return P{xy[2 * (n - 1 - i)], xy[2 * (n - 1 - i) + 1]}; });
      else if (how == Copied) {
        const std::vector<P>& v = copies_.at(k);
        walk(v.size(), [&](std::size_t i) { return v[i]; });
      }
      ++k;
    });
  }

 private:
  enum How : std::uint8_t { Skip, Forward, Backward, Copied };
  const PolygonIndex& layer_;
  std::vector<std::size_t> first_;  // polygon p's rings: [first_[p], first_[p + 1])
  std::vector<How> how_;            // a byte a ring: a full layer has millions
  std::unordered_map<std::size_t, std::vector<P>> copies_;  // the few rings simplifying changed
};

std::vector<std::uint64_t> context_ids(const PolygonIndex& layer, const BoxTree& boxes, const double* at,
                                       std::size_t n_points, std::int64_t radius, int threads) {
  if (radius < 1 || radius >= (std::int64_t(1) << 26)) throw std::invalid_argument("context radius must be in [1, 2^26) DBU");
  for (std::size_t i = 0; i < 2 * n_points; ++i) half_units(at[i]);
  const std::int64_t R = 2 * radius;
  std::vector<std::uint64_t> ids(n_points);
  const PreparedRings rings(layer, threads);
  constexpr std::size_t kBatch = 256;
  const std::size_t batches = (n_points + kBatch - 1) / kBatch;
  std::vector<std::vector<std::size_t>> hits(detail::worker_count(batches, threads));
  detail::parallel_for(batches, threads, [&](unsigned w, std::size_t b) {
    std::vector<std::size_t>& met = hits[w];
    Window win(R);
    for (std::size_t i = b * kBatch; i < std::min(n_points, (b + 1) * kBatch); ++i) {
      const std::int64_t cx = half_units(at[2 * i]), cy = half_units(at[2 * i + 1]);
      // The window in DBU, widened to whole units: a polygon met only by the widening adds
      // nothing (its crossings left of the window come in pairs).
      const IntBox q{floor_half(cx - R), floor_half(cy - R), floor_half(cx + R + 1), floor_half(cy + R + 1)};
      met.clear();
      boxes.query(q, [&](std::int32_t id) { met.push_back(std::size_t(id)); });
      win.clear();
      for (std::size_t p : met) rings.edges(p, cx, cy, win);
      ids[i] = canonical_id(win.segments(), R);
    }
  });
  return ids;
}

std::vector<std::uint64_t> context_ids(const FlatPolygons& layer, const std::vector<double>& at, std::int64_t radius,
                                       int threads) {
  if (at.size() % 2 != 0) throw std::invalid_argument("context points must be x, y pairs");
  const PolygonIndex ix(layer);
  const BoxTree boxes(ix.size(), [&](std::size_t i) { return ix.box(i); });
  return context_ids(ix, boxes, at.data(), at.size() / 2, radius, threads);
}

}  // namespace linf
