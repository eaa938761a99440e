// libFuzzer target: small layouts through the core at every scale it supports, with
// independent oracles. Each input (format in input.hpp) decodes to rectilinear, octilinear or
// any-angle polygons (boxes, frames, staircases with corner cuts, free rings, may overlap or
// self-intersect) or to plain segments and points, scaled and placed anywhere from the origin
// to the +-2^30 limit and a little beyond, with the builder's options (tiles, tie-break,
// far-field pass) varied. Findings, each aborting the run:
//   the diagram: the checker rejects it (DiagramError), unless a known fault that is not fixed
//     yet explains it (known.hpp: counted and reported when the run ends); or a piece ends where
//     its owners still own either side beyond it (ends_check.hpp: a piece missing); or the
//     sweep-line builder's pieces differ from it (sweep_check.hpp; unless a known fault of
//     the subdivision explains it and the sweep passes a full check, or the sweep's known
//     fault in tiles does and its whole layer's pieces match: known.hpp), or its pieces in
//     tiles differ from its whole layer's by a bit;
//   the farthest diagram of crossing segments, points and convex polygons taken from the same
//     shapes: a vertex off its weight, or a face, edge or region whose owners are not the
//     farthest sites by brute force, or the root not the least weight (farthest_check.hpp);
//   the range: input inside +-2^30 refused, or input beyond it accepted or refused with another
//     error than the documented std::invalid_argument;
//   any crash, leak, uncaught exception or AddressSanitizer / UndefinedBehaviorSanitizer report.
// Built and run by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined), seeded from
// tests/fuzz/corpus/ (written by fuzz_seeds.cpp, grown from findings).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "ends_check.hpp"
#include "farthest_check.hpp"
#include "input.hpp"
#include "known.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/farthest/farthest.hpp"
#include "plain.hpp"
#include "sweep_check.hpp"
#include "linf/diagram/sweep.hpp"

using namespace linf;
using namespace linf::fuzz;

namespace {

[[noreturn]] void fail(const char* stage, const char* what) {
  std::fprintf(stderr, "fuzz finding in %s: %s\n", stage, what);
  std::abort();
}

bool in_range(const Point& p) { return p.x > -kLimit && p.x < kLimit && p.y > -kLimit && p.y < kLimit; }

// Runs a stage on input that is inside the limit (`valid`) or not: a computed (and checked)
// result, or the documented refusal, whichever is due. A diagram rejected by the checker is a
// finding unless a known fault (known.hpp) explains it.
template <class Run>
void expect(const char* stage, bool valid, known::Fault fault, Run&& run) {
  try {
    run();
  } catch (const DiagramError& e) {
    if (!valid) fail(stage, "built a diagram of a coordinate beyond +-2^30");
    if (fault == known::None || known::strict()) fail(stage, e.what());
    known::count(fault);
    return;
  } catch (const std::invalid_argument& e) {
    if (valid) fail(stage, (std::string("refused input inside +-2^30: ") + e.what()).c_str());
    if (!std::strstr(e.what(), "2^30"))
      fail(stage, (std::string("refused input beyond 2^30 with: ") + e.what()).c_str());
    return;
  }
  if (!valid) fail(stage, "accepted a coordinate beyond +-2^30");
}

DiagramOptions options_of(const Layout& L) {
  DiagramOptions o;
  o.build.threads = 1;  // deterministic coverage, one core
  if (L.options & 1) o.build.tile_size = double(L.extent) / (2 + ((L.options >> 1) & 3));
  o.build.axis_ties = !(L.options & 8);
  o.build.far_field_pass = !(L.options & 16);
  return o;
}

// A diagram the checker passed must have no piece that ends while its edge goes on.
void ends(const Result& r) {
  const EndsReport e = check_piece_ends(r.diagram);
  if (!e.failure.empty()) fail("the diagram's piece ends", e.failure.c_str());
}

// The sweep-line builder's pieces must be the subdivision's (it takes every layer).
void sweep(const Layout& L, DiagramOptions opt, const Result& subdivision) {
  if (!sweep_handles(subdivision.diagram.sites)) return;
  opt.sweep = true;
  opt.check = false;
  const Result r = voronoi_of_polygons(L.polygons, opt);
  if (!r.diagram.swept) fail("the sweep", "did not build a layer it takes");
  // Within the subdivision's own allowance (builder.cpp, allowance(): 1e-12 of the clip box).
  const Box& c = subdivision.diagram.clip;
  const double floor = 1e-12 * std::max({1.0, std::fabs(c.x1), std::fabs(c.x2), std::fabs(c.y1), std::fabs(c.y2)});
  std::pair<int, int> at{-1, -1};
  const std::string d = same_pieces(subdivision.diagram.pieces, r.diagram.pieces, 1e-9, floor, &at);
  if (!d.empty()) {
    const known::Fault f = known::of_comparison(subdivision.diagram.sites.sites, at);
    if (f == known::None || known::strict()) fail("the sweep against the subdivision", d.c_str());
    // The sweep, then, passes a full check (every piece searched, ten times the pairs).
    CheckOptions full;
    full.search_every = 1, full.crossing_pairs = 20000, full.threads = 1;
    const CheckReport checked = check_diagram(r.diagram, full);
    if (!checked.ok())
      fail("the sweep's full check", checked.messages.empty() ? "failed" : checked.messages[0].c_str());
    known::count(f);
  }
  if (opt.build.tile_size == 0) return;
  // In tiles: the whole layer's sweep, bit for bit.
  opt.build.tile_size = 0;
  const std::vector<Piece>& tiled = r.diagram.pieces;
  const std::vector<Piece> whole = voronoi_of_polygons(L.polygons, opt).diagram.pieces;
  bool same = tiled.size() == whole.size();
  for (std::size_t i = 0; same && i < tiled.size(); ++i)
    same = tiled[i].a == whole[i].a && tiled[i].b == whole[i].b && tiled[i].p.x == whole[i].p.x &&
           tiled[i].p.y == whole[i].p.y && tiled[i].q.x == whole[i].q.x && tiled[i].q.y == whole[i].q.y;
  if (!same) fail("the sweep in tiles", "differs from the whole layer's sweep");
}

void diagram_stage(const Layout& L) {
  const DiagramOptions opt = options_of(L);
  std::vector<Point> all;
  std::vector<Segment> edges;
  if (L.style != Plain) {
    auto add = [&](const Ring& r) {
      for (std::size_t i = 0; i < r.size(); ++i) all.push_back(r[i]), edges.push_back({r[i], r[(i + 1) % r.size()]});
    };
    for (const Polygon& p : L.polygons) {
      add(p.outer);
      for (const Ring& h : p.holes) add(h);
    }
    const bool valid = std::all_of(all.begin(), all.end(), in_range);
    expect("the diagram of polygons", valid, known::of_diagram(all, edges, opt.build.axis_ties), [&] {
      const Result r = voronoi_of_polygons(L.polygons, opt);
      ends(r);
      sweep(L, opt, r);
    });
    return;
  }
  std::vector<Segment> segments;
  std::vector<Point> points;
  for (const Segment& s : non_crossing(L.items)) {
    (s.a == s.b ? points.push_back(s.a) : segments.push_back(s));
    all.push_back(s.a), all.push_back(s.b);
  }
  const bool valid = std::all_of(all.begin(), all.end(), in_range);
  expect("the diagram of segments and points", valid, known::of_diagram(all, segments, opt.build.axis_ties),
         [&] { ends(voronoi_of_sites(points, segments, opt)); });
}

// The sites of the farthest diagram: each polygon's diagonal from its first vertex and its
// outer ring's edges (segments that cross, touch and repeat) and, if asked, the ring itself (a
// convex polygon site: its hull); or the items.
std::vector<std::vector<Point>> farthest_sites(const Layout& L) {
  std::vector<std::vector<Point>> sites;
  auto segment = [&](const Point& a, const Point& b) {
    sites.push_back(a == b ? std::vector<Point>{a} : std::vector<Point>{a, b});
  };
  for (const Polygon& p : L.polygons) {
    const Ring& r = p.outer;
    segment(r[0], r[r.size() / 2]);
    for (std::size_t i = 0; i < r.size(); ++i) segment(r[i], r[(i + 1) % r.size()]);
    if (L.polygon_sites) sites.push_back(r);
  }
  for (const Segment& s : L.items) segment(s.a, s.b);
  return sites;
}

void farthest_stage(const Layout& L, std::uint64_t seed) {
  const auto sites = farthest_sites(L);
  bool valid = true;
  for (const auto& s : sites)
    for (const Point& q : s) valid &= in_range(q);
  expect("the farthest diagram", valid, known::None, [&] {
    const FarthestDiagram d = farthest_voronoi(sites);
    FarthestCheck check(sites, d);
    const std::string failure = check.run(seed);
    if (!failure.empty()) fail("the farthest diagram", failure.c_str());
  });
}

std::uint64_t hash(const std::uint8_t* data, std::size_t size) {  // FNV-1a: the sample points
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Layout L = decode(data, size);
  diagram_stage(L);
  farthest_stage(L, hash(data, size));
  return 0;
}
