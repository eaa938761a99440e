#include "linf/gauges/stretch.hpp"

#include "gauges/chain.hpp"

#include "linf/geometry/distance.hpp"
#include "linf/util/pages.hpp"
#include "linf/util/round.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace linf {

using detail::chain;
using detail::Key;
using detail::key_of;

bool adjacent(const Sites& s, std::int32_t a, std::int32_t b) {
  const Site& x = s.sites[a];
  const Site& y = s.sites[b];
  const std::int32_t fx[3] = {a, x.end0, x.end1};
  const std::int32_t fy[3] = {b, y.end0, y.end1};
  for (std::int32_t i : fx)
    for (std::int32_t j : fy)
      if (i >= 0 && i == j) return true;
  return false;
}

namespace {

// A point stretch: a pair without a chain whose regions meet at a vertex; added after the chains,
// in the order of the vertices (their keys).
struct PointStretch {
  std::int32_t a, b;
  PieceKind kind;
  Vec2 at;
  double clearance;
  Key key;
};

// One piece end at a vertex: what the vertex needs of it.
struct End {
  Vec2 at;
  double clearance;
  std::int32_t a, b;
  PieceKind kind;
};

// An end at a vertex on a part's frame, held until every part is in.
struct Held {
  Key key;
  End end;
};

// The pairs meeting at one vertex (the piece ends `end(0..n-1)` sharing one key) that `keep`
// accepts and that have no chain. Nothing here depends on the order of the ends: a diagram
// that comes in parts gives the same point stretches as a whole one.
template <class EndAt, class HasChain, class Out>
void vertex(const Key& key, std::size_t n, const EndAt& end, const Sites& sites, const StretchFilter& keep,
            const HasChain& has_chain, std::vector<std::int32_t>& owners, Out& out) {
  if (n < 2) return;
  // Where the ends differ by rounding, the greatest (x, y, clearance) gives the vertex.
  End top = end(0);
  bool side = false, internal = false;  // some end not between adjacent sites; one inside
  owners.clear();
  for (std::size_t e = 0; e < n; ++e) {
    const End x = end(e);
    if (std::tie(x.at.x, x.at.y, x.clearance) > std::tie(top.at.x, top.at.y, top.clearance)) top = x;
    if (x.kind != PieceKind::Adjacent) side = true, internal = internal || x.kind == PieceKind::Internal;
    owners.push_back(x.a);
    owners.push_back(x.b);
  }
  if (!(top.clearance > 0) || !side) return;  // on the boundary, or only between adjacent sites
  std::sort(owners.begin(), owners.end());
  owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
  if (owners.size() < 3) return;
  // The pieces around a vertex off the boundary agree on the side (inside or outside).
  for (std::size_t i = 0; i < owners.size(); ++i)
    for (std::size_t j = i + 1; j < owners.size(); ++j) {
      const std::int32_t a = owners[i], b = owners[j];
      const PieceKind sk = internal                                                ? PieceKind::Internal
                           : sites.sites[a].shape == sites.sites[b].shape ? PieceKind::Notch
                                                                           : PieceKind::External;
      if (adjacent(sites, a, b) || (keep && !keep(a, b, sk)) || has_chain(a, b)) continue;
      out.push_back({a, b, sk, top.at, top.clearance, key});
    }
}

End end_of(const Piece* pieces, std::uint32_t e) {
  const Piece& p = pieces[e >> 1];
  return e & 1 ? End{p.q, p.d2, p.a, p.b, p.kind} : End{p.p, p.d1, p.a, p.b, p.kind};
}

// A piece end (piece << 1 | end) with its position's key.
struct KeyedEnd {
  Key key;
  std::uint32_t end;
  bool operator<(const KeyedEnd& o) const { return key < o.key || (key == o.key && end < o.end); }
};

// The ends of `n` pieces (a part: a tile's in the stream) sorted by position, then by end, 24
// bytes an end (a piece takes 64). The keys are computed once and sorted with the ends: a sort
// of indices that looked the pieces up and rounded their ends in every comparison was a
// quarter of the gauge stage.
std::vector<KeyedEnd> sorted_ends(const Piece* pieces, std::size_t n) {
  std::vector<KeyedEnd> ends(2 * n);
  for (std::uint32_t i = 0; i < ends.size(); ++i) ends[i] = {key_of(i & 1 ? pieces[i >> 1].q : pieces[i >> 1].p), i};
  std::sort(ends.begin(), ends.end());
  return ends;
}

std::pair<std::int32_t, std::int32_t> pair_of(const Piece& p) { return {std::min(p.a, p.b), std::max(p.a, p.b)}; }

// Point stretches go after the chains, in vertex order.
void add_points(const Paged<PointStretch>& points, Stretches& out) {
  for (const PointStretch& m : points) {
    out.open(m.a, m.b, m.kind);
    out.add(m.at, m.clearance);
  }
}

// Room reserved at once: pages are committed only as they are written, where vectors growing
// by doubling would hold up to three times the stretches while they reallocate. A stretch has
// at most its pieces' ends (a few more where a diagonal dip is refined); point stretches come
// on top.
void reserve_for(std::size_t kept, std::size_t pieces, Stretches& out) {
  out.reserve(kept + pieces / 4 + 64, 2 * kept + pieces / 4 + 64);
}

bool grouped(const std::vector<Piece>& pieces) {
  return std::is_sorted(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return pair_of(x) < pair_of(y); });
}

// A whole diagram is a stream of one part with no frame (every vertex is complete where it
// is), so there is one way to build stretches. `pieces` are grouped by owner pair;
// done(n) is told after the first n pieces are used.
template <class Done>
Stretches in_one_part(const Sites& sites, const std::vector<Piece>& pieces, const StretchFilter& keep, Done&& done) {
  StretchStream stream(sites, keep, pieces.size());
  const double none = std::numeric_limits<double>::infinity();
  stream.part(pieces, Box{none, none, none, none});
  for (std::size_t g0 = 0; g0 < pieces.size();) {
    std::size_t g1 = g0 + 1;
    while (g1 < pieces.size() && pair_of(pieces[g1]) == pair_of(pieces[g0])) ++g1;
    stream.pair(pieces.data() + g0, g1 - g0);
    g0 = g1;
    done(g0);
  }
  return stream.finish();
}

}  // namespace

Stretches stretches_of(const Diagram& d, const StretchFilter& keep) {
  auto nothing = [](std::size_t) {};
  if (grouped(d.pieces)) return in_one_part(d.sites, d.pieces, keep, nothing);
  std::vector<Piece> pieces = d.pieces;  // not the builder's order
  std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return pair_of(x) < pair_of(y); });
  return in_one_part(d.sites, pieces, keep, nothing);
}

Stretches take_stretches(Diagram& d, const StretchFilter& keep) {
  if (!grouped(d.pieces)) {
    Stretches out = stretches_of(d, keep);
    std::vector<Piece>().swap(d.pieces);
    return out;
  }
  std::size_t released = 0;  // pieces before this are consumed and their pages given back
  Stretches out = in_one_part(d.sites, d.pieces, keep, [&](std::size_t used) {
    if (used - released >= (std::size_t(1) << 16)) {  // 4 MB of pieces at a time
      detail::release_pages(d.pieces.data() + released, d.pieces.data() + used);
      released = used;
    }
  });
  std::vector<Piece>().swap(d.pieces);
  return out;
}

void Stretches::keep_only(const std::vector<bool>& keep) {
  std::size_t h = 0, at = 0;
  for (std::size_t i = 0; i < heads_.size(); ++i) {
    if (!keep[i]) continue;
    Head x = heads_[i];
    std::copy(points_.begin() + x.first, points_.begin() + x.first + x.count, points_.begin() + at);
    std::copy(clearance_.begin() + x.first, clearance_.begin() + x.first + x.count, clearance_.begin() + at);
    x.first = std::uint32_t(at);
    at += x.count;
    heads_[h++] = x;
  }
  heads_.resize(h);
  points_.resize(at);
  clearance_.resize(at);
}

struct StretchStream::Impl {
  const Sites& sites;
  StretchFilter keep;
  Stretches out;
  // Both grow with the layer (a few per wire): in Paged arrays, as the stretches are.
  Paged<PointStretch> points;  // from complete vertices; chains not yet known everywhere
  Paged<Held> held;            // ends at vertices on a part's frame
  std::vector<std::int32_t> owners, ids;
  bool pairs_started = false;
};

StretchStream::StretchStream(const Sites& sites, StretchFilter keep, std::size_t expected_pieces)
    : impl_(std::make_unique<Impl>(Impl{sites, std::move(keep), {}, {}, {}, {}, {}, false})) {
  reserve_for(expected_pieces / 2, expected_pieces, impl_->out);
}

StretchStream::~StretchStream() = default;

// A part's vertices: the point stretches of those away from its frame, the ends of those on it.
struct StretchStream::Reading {
  std::vector<PointStretch> points;
  std::vector<Held> held;
};

std::shared_ptr<const StretchStream::Reading> StretchStream::read(const std::vector<Piece>& part, const Box& frame) const {
  auto r = std::make_shared<Reading>();
  read_into(part, frame, *r);
  return r;
}

void StretchStream::read_into(const std::vector<Piece>& part, const Box& frame, Reading& r) const {
  const Impl& m = *impl_;
  // A vertex farther than this from the frame has all its pieces in this part: pieces stop at
  // the frame, and no end of another part can round to its key (1/1024 DBU).
  const double eps = 1.0 / 64;
  auto on_frame = [&](const Vec2& v) {
    return std::fabs(v.x - frame.x1) <= eps || std::fabs(v.x - frame.x2) <= eps || std::fabs(v.y - frame.y1) <= eps ||
           std::fabs(v.y - frame.y2) <= eps;
  };
  // A chain in this part settles a pair; one elsewhere is looked for in finish().
  auto has_chain_here = [&](std::int32_t a, std::int32_t b) {
    const auto pr = std::make_pair(a, b);
    auto it = std::lower_bound(part.begin(), part.end(), pr, [](const Piece& x, const std::pair<std::int32_t, std::int32_t>& v) {
      return pair_of(x) < v;
    });
    for (; it != part.end() && pair_of(*it) == pr; ++it)
      if (!m.keep || m.keep(a, b, it->kind)) return true;
    return false;
  };
  std::vector<std::int32_t> owners;
  const std::vector<KeyedEnd> ends = sorted_ends(part.data(), part.size());
  for (std::size_t g0 = 0; g0 < ends.size();) {
    const Key k = ends[g0].key;
    std::size_t g1 = g0 + 1;
    bool framed = on_frame(end_of(part.data(), ends[g0].end).at);
    for (; g1 < ends.size() && ends[g1].key == k; ++g1)
      framed = framed || on_frame(end_of(part.data(), ends[g1].end).at);
    if (framed) {
      for (std::size_t e = g0; e < g1; ++e) r.held.push_back({k, end_of(part.data(), ends[e].end)});
    } else {
      vertex(k, g1 - g0, [&](std::size_t e) { return end_of(part.data(), ends[g0 + e].end); }, m.sites, m.keep,
             has_chain_here, owners, r.points);
    }
    g0 = g1;
  }
}

namespace {

template <class T>
void put_all(std::string& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}

template <class T>
std::vector<T> get_all(const std::string& in, std::size_t& at) {
  std::uint64_t n = 0;
  if (in.size() - at < sizeof n) throw std::invalid_argument("a tile's stretch reading is truncated");
  std::memcpy(&n, in.data() + at, sizeof n);
  at += sizeof n;
  if (n > (in.size() - at) / sizeof(T)) throw std::invalid_argument("a tile's stretch reading is truncated");
  std::vector<T> v(n);
  if (n) std::memcpy(static_cast<void*>(v.data()), in.data() + at, n * sizeof(T));
  at += n * sizeof(T);
  return v;
}

}  // namespace

std::string StretchStream::read_bytes(const std::vector<Piece>& part, const Box& frame,
                                      const std::vector<int>& global) const {
  Reading r;
  read_into(part, frame, r);
  const auto to = [&](std::int32_t& id) { id = global.at(std::size_t(id)); };
  for (PointStretch& p : r.points) to(p.a), to(p.b);
  for (Held& h : r.held) to(h.end.a), to(h.end.b);
  std::string out;
  put_all(out, r.points);
  put_all(out, r.held);
  return out;
}

std::shared_ptr<const StretchStream::Reading> StretchStream::reading(const std::string& bytes) {
  auto r = std::make_shared<Reading>();
  std::size_t at = 0;
  r->points = get_all<PointStretch>(bytes, at);
  r->held = get_all<Held>(bytes, at);
  if (at != bytes.size()) throw std::invalid_argument("a tile's stretch reading is malformed");
  return r;
}

void StretchStream::add(const Reading& r) {
  Impl& m = *impl_;
  if (m.pairs_started) throw std::logic_error("StretchStream: every part comes before the pairs");
  for (const PointStretch& p : r.points) m.points.push_back(p);
  for (const Held& h : r.held) m.held.push_back(h);
}

void StretchStream::part(const std::vector<Piece>& part, const Box& frame) { add(*read(part, frame)); }

void StretchStream::pair(const Piece* pieces, std::size_t n) {
  Impl& m = *impl_;
  m.pairs_started = true;
  if (n == 0) return;
  const auto pr = pair_of(pieces[0]);
  m.ids.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (!m.keep || m.keep(pr.first, pr.second, pieces[i].kind)) m.ids.push_back(std::int32_t(i));
  if (!m.ids.empty()) chain(m.sites, pieces, m.ids.data(), m.ids.size(), m.out);
}

Stretches StretchStream::finish() {
  Impl& m = *impl_;
  std::sort(m.held.begin(), m.held.end(), [](const Held& x, const Held& y) { return x.key < y.key; });
  auto none = [](std::int32_t, std::int32_t) { return false; };
  for (std::size_t g0 = 0; g0 < m.held.size();) {
    std::size_t g1 = g0 + 1;
    while (g1 < m.held.size() && m.held[g1].key == m.held[g0].key) ++g1;
    vertex(m.held[g0].key, g1 - g0, [&](std::size_t e) { return m.held[g0 + e].end; }, m.sites, m.keep, none,
           m.owners, m.points);
    g0 = g1;
  }
  m.held = Paged<Held>();
  // The chains are in pair order: a pair has one when a stretch opens with it.
  const Stretches& st = m.out;
  const std::size_t chains = st.size();
  auto has_chain = [&](std::int32_t a, std::int32_t b) {
    std::size_t lo = 0, hi = chains;
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      const Stretch x = st[mid];
      if (std::make_pair(x.a, x.b) < std::make_pair(a, b)) lo = mid + 1;
      else hi = mid;
    }
    return lo < chains && st[lo].a == a && st[lo].b == b;
  };
  m.points.resize(std::size_t(std::remove_if(m.points.begin(), m.points.end(), [&](const PointStretch& p) { return has_chain(p.a, p.b); }) -
                              m.points.begin()));
  // Vertex order. A vertex's pairs are distinct and were made in ascending order, so sorting
  // by (key, a, b) keeps them as a stable sort would, without a stable sort's copy of them.
  std::sort(m.points.begin(), m.points.end(), [](const PointStretch& x, const PointStretch& y) {
    return x.key < y.key || (x.key == y.key && std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b));
  });
  add_points(m.points, m.out);
  return std::move(m.out);
}

}  // namespace linf
