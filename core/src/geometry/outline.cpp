#include "outline.hpp"

#include "util/parallel.hpp"

namespace linf::detail {

namespace {

// Up to this many points an outline's edges are tested pairwise (about 2,000 tests at most, far
// less than the scan), above through an index of them, held while merging: 20 bytes an edge,
// of the large polygons only.
constexpr std::size_t kFew = 64;
// Larger polygons go to the scan.
constexpr std::size_t kMostPoints = std::size_t(1) << 16;

// Do closed segments ab and cd meet?
bool meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
      std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
    return false;
  const __int128 d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  // On the other segment's line and within the pair's common box: on that segment.
  auto on = [](const Point& p, const Point& q, const Point& r) {
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) || (d4 == 0 && on(a, b, d));
}

// Does edge k of o cross the ray from p to +x (half-open in y, so a vertex on the ray counts
// once)? p is on no edge.
bool crosses_ray(const Outline& o, std::size_t k, const Point& p) {
  const Point a = o[k], b = o.edge_end(k);
  if ((a.y > p.y) == (b.y > p.y)) return false;
  const __int128 c = cross(a, b, p);
  return b.y > a.y ? c > 0 : c < 0;
}

}  // namespace

IntBox Outline::edge_box(std::size_t k) const {
  const Point a = (*this)[k], b = edge_end(k);
  return {std::int32_t(std::min(a.x, b.x)), std::int32_t(std::min(a.y, b.y)), std::int32_t(std::max(a.x, b.x)),
          std::int32_t(std::max(a.y, b.y))};  // coordinates are checked by PolygonIndex
}

Outline Outlines::outline(std::size_t i) const {
  Outline o;
  ix_.rings(i, [&](const std::int64_t* xy, std::size_t n, bool outer) {
    if (outer) o.xy = xy, o.n = n;
    else o.holes = true;
  });
  return o;
}

Outlines::Outlines(const PolygonIndex& ix, int threads) : ix_(ix) {
  const std::size_t n = ix.size();
  plain_.resize(n);
  tree_of_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = ix.points(i);
    tree_of_[i] = k > kFew && k <= kMostPoints ? std::int32_t(trees_.size()) : -1;
    if (tree_of_[i] >= 0) trees_.emplace_back();
  }
  constexpr std::size_t kChunk = 1024;
  parallel_for((n + kChunk - 1) / kChunk, threads, [&](unsigned, std::size_t c) {
    for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      const Outline o = outline(i);
      if (o.holes || o.n < 3 || o.n > kMostPoints) continue;
      BoxTree* edges = nullptr;
      if (tree_of_[i] >= 0) {
        edges = &trees_[std::size_t(tree_of_[i])];
        *edges = BoxTree(o.n, [&](std::size_t k) { return o.edge_box(k); });
      }
      plain_[i] = simple(o, edges);
      if (!plain_[i] && edges) *edges = BoxTree();
    }
  });
}

bool Outlines::simple(const Outline& o, const BoxTree* edges) const {
  const std::size_t n = o.n;
  for (std::size_t i = 0; i < n; ++i)
    if (o[i] == o.edge_end(i) || cross(o[(i + n - 1) % n], o[i], o.edge_end(i)) == 0) return false;
  // Neighbours meet at their vertex only, as no vertex is straight or turns back.
  auto apart = [&](std::size_t i, std::size_t j) {
    if (j < i) std::swap(i, j);
    return j < i + 2 || (i == 0 && j + 1 == n) || !detail::meet(o[i], o.edge_end(i), o[j], o.edge_end(j));
  };
  if (!edges) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j)
        if (!apart(i, j)) return false;
    return true;
  }
  bool ok = true;
  for (std::size_t i = 0; i < n && ok; ++i)
    edges->query(o.edge_box(i), [&](std::int32_t j) { ok = ok && (std::size_t(j) <= i || apart(i, std::size_t(j))); });
  return ok;
}

bool Outlines::inside(const Point& p, std::size_t i) const {
  const Outline o = outline(i);
  bool in = false;
  if (tree_of_[i] < 0) {
    for (std::size_t k = 0; k < o.n; ++k) in ^= crosses_ray(o, k, p);
    return in;
  }
  // The edges that cross the ray meet its part within the polygon's box.
  const IntBox ray{std::int32_t(p.x), std::int32_t(p.y), std::max(std::int32_t(p.x), ix_.box(i).x2), std::int32_t(p.y)};
  trees_[std::size_t(tree_of_[i])].query(ray, [&](std::int32_t k) { in ^= crosses_ray(o, std::size_t(k), p); });
  return in;
}

bool Outlines::meet(std::size_t i, std::size_t j) const {
  if (ix_.points(i) > ix_.points(j)) std::swap(i, j);  // i the smaller
  const Outline a = outline(i), b = outline(j);
  const IntBox& bb = ix_.box(j);
  bool met = false;
  for (std::size_t k = 0; k < a.n && !met; ++k) {
    const IntBox e = a.edge_box(k);
    if (!e.intersects(bb)) continue;
    auto test = [&](std::size_t m) { met = met || detail::meet(a[k], a.edge_end(k), b[m], b.edge_end(m)); };
    if (tree_of_[j] >= 0) trees_[std::size_t(tree_of_[j])].query(e, [&](std::int32_t m) { test(std::size_t(m)); });
    else
      for (std::size_t m = 0; m < b.n && !met; ++m) test(m);
  }
  // No edges meet, so each vertex of one is inside the other or outside it.
  return met || inside(a[0], j) || inside(b[0], i);
}

Ring Outlines::as_merged(std::size_t i) const {
  const Outline o = outline(i);
  Ring r(o.n);
  for (std::size_t k = 0; k < o.n; ++k) r[k] = o[k];
  r = oriented(std::move(r), true);
  std::rotate(r.begin(), std::max_element(r.begin(), r.end()), r.end());
  return r;
}

}  // namespace linf::detail
