// The sweep-line builder against Boost.Polygon's Euclidean construct_voronoi and the
// subdivision builder, on the same point sites, one thread each, in one run.
//
//   build/bench_sweep [runs=3] [max_points=1000000]      generated point sets and wires (some with 45-degree jogs)
//   build/bench_sweep runs NAME FILE [NAME FILE ...]       layers (bench/bench_sweep_layers.py)
//   build/bench_sweep tiles runs [NAME FILE ...]           the sweep in tiles, 1 and 2 threads
//   build/bench_sweep memory WIRES TILE THREADS             one build, for /usr/bin/time -v
//   build/bench_sweep curved runs                          disks, a ring and round pads (slanted edges)
//   build/bench_sweep check runs NAME FILE|wires:N ...     the checker, sampled and full, against the build
//   build/bench_sweep wires runs N ...                     generated wires of N rectangles, no subdivision
//
// Prints one markdown row an input: the best of `runs` timings of each (alternating), the
// ratios sweep / Boost and subdivision / sweep, and whether the two L-inf builders gave the
// same number of pieces. A layer is merged first; Boost gets its merged edges as segments,
// ours the same edges and their vertices as sites. FILE: one ring a line, "o" (an outer ring)
// or "h" (a hole of the last outer ring) and its x y pairs in DBU.
#include <algorithm>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/diagram/sweep.hpp"
#include "linf/geometry/sites.hpp"

using namespace linf;

namespace {

double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Point> random_points(std::size_t n, int range, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> c(0, range);
  std::set<std::pair<int, int>> seen;
  std::vector<Point> p;
  while (p.size() < n) {
    const int x = c(rng), y = c(rng);
    if (seen.insert({x, y}).second) p.push_back({x, y});
  }
  return p;
}

// The corners of a block of wires: rows of rectangles 16-48 DBU wide, 32-DBU spaces, on a
// 64-DBU row pitch (a routed metal layer's vertices: many on one line, many on one diagonal).
std::vector<Point> wire_corners(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> len(40, 400), width(16, 48);
  std::vector<Point> p;
  const int rows = int(std::sqrt(double(n) / 4 / 8)) + 1;
  std::vector<int> x(rows, 0);
  for (int r = 0; p.size() < n; r = (r + 1) % rows) {
    const int w = width(rng), l = len(rng), y = r * 64;
    p.push_back({x[r], y}), p.push_back({x[r] + l, y}), p.push_back({x[r] + l, y + w}), p.push_back({x[r], y + w});
    x[r] += l + 32;
  }
  p.resize(n);
  return p;
}

// The same block of wires as rectangles (a Manhattan layer of n wires: 4n edges).
std::vector<Polygon> wires(std::size_t n, std::uint64_t seed) {
  const std::vector<Point> c = wire_corners(4 * n, seed);
  std::vector<Polygon> out;
  for (std::size_t i = 0; i + 3 < c.size(); i += 4) out.push_back({{c[i], c[i + 1], c[i + 2], c[i + 3]}, {}});
  return out;
}

// The same rows with a 45-degree jog in each wire: up 16 DBU along a diagonal band of the
// wire's width (an octilinear layer: 8n edges, a quarter of them at 45 degrees).
std::vector<Polygon> bent_wires(std::size_t n, std::uint64_t seed) {
  const std::vector<Point> c = wire_corners(4 * n, seed);
  std::vector<Polygon> out;
  for (std::size_t i = 0; i + 3 < c.size(); i += 4) {
    const Coord x = c[i].x, y = c[i].y, l = c[i + 1].x - x, w = std::min<Coord>(c[i + 2].y - y, 32), h = 16;
    const Coord a = (l - h) / 2;
    out.push_back({{{x, y}, {x + a, y}, {x + a + h, y + h}, {x + l, y + h}, {x + l, y + h + w}, {x + a + h, y + h + w},
                    {x + a, y + w}, {x, y + w}},
                   {}});
  }
  return out;
}

// One row; returns the sweep's best time.
double row(const std::string& name, const Sites& s, int runs, bool with_subdivision = true) {
  std::vector<boost::polygon::point_data<int>> bp;
  std::vector<boost::polygon::segment_data<int>> bs;
  std::size_t n = 0;
  for (const Site& t : s.sites) {
    if (t.is_point()) ++n;
    if (t.is_point() && t.ring < 0) bp.push_back({int(t.a.x), int(t.a.y)});
    if (!t.is_point()) bs.push_back({{int(t.a.x), int(t.a.y)}, {int(t.b.x), int(t.b.y)}});
  }
  const Box clip = clip_box(s);
  BuildOptions one;
  one.threads = 1;
  double tb = 1e30, ts = 1e30, tsub = 1e30;
  std::size_t ns = 0, nsub = 0;
  for (int r = 0; r < runs; ++r) {
    tb = std::min(tb, seconds([&] {
      boost::polygon::voronoi_diagram<double> vd;
      boost::polygon::construct_voronoi(bp.begin(), bp.end(), bs.begin(), bs.end(), &vd);
    }));
    ts = std::min(ts, seconds([&] { ns = sweep_pieces(s, clip).size(); }));
    if (with_subdivision) tsub = std::min(tsub, seconds([&] { nsub = build_pieces(s, clip, one).size(); }));
  }
  if (!with_subdivision) {
    std::printf("| %s | %zu / %zu | %.3f s | %.3f s | — | %.2f | — | — |\n", name.c_str(), n, bs.size(), tb, ts, ts / tb);
    std::fflush(stdout);
    return ts;
  }
  std::printf("| %s | %zu / %zu | %.3f s | %.3f s | %.3f s | %.2f | %.2f | %s |\n", name.c_str(), n, bs.size(), tb, ts, tsub,
              ts / tb, tsub / ts, ns == nsub ? "yes" : "NO");
  std::fflush(stdout);
  return ts;
}

// A disk drawn with n vertices (rounded to the grid, repeats dropped), counter-clockwise.
Ring disk(Coord cx, Coord cy, double r, int n) {
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    const Point p{cx + Coord(std::lround(r * std::cos(a))), cy + Coord(std::lround(r * std::sin(a)))};
    if (ring.empty() || !(ring.back() == p)) ring.push_back(p);
  }
  return ring;
}

// Curved shapes (slanted edges of every slope: the sweep's 256-bit balls) against Boost and the
// subdivision, then each one's sweep time a site against a Manhattan layer's (generated wires)
// in the same run.
void curved(int runs) {
  std::vector<std::pair<std::string, std::vector<Polygon>>> inputs;
  inputs.push_back({"disk, 4,096 vertices, r = 10^7 DBU", {{disk(0, 0, 1e7, 4096), {}}}});
  inputs.push_back({"disk, 2,048 vertices, r = 50,000 DBU (near-collinear runs)", {{disk(0, 0, 50000, 2048), {}}}});
  Ring hole = disk(120000, -70000, 4e5, 512);
  std::reverse(hole.begin(), hole.end());
  inputs.push_back({"ring, 1,024 + 512 vertices", {{disk(0, 0, 1e6, 1024), {hole}}}});
  std::vector<Polygon> pads;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j) pads.push_back({disk(900 * i, 900 * j + (i % 2) * 300, 300 + (i * 7 + j * 13) % 60, 64), {}});
  inputs.push_back({"2,500 round pads of 64 vertices", pads});
  std::vector<std::pair<std::string, double>> per_site;
  for (const auto& in : inputs) {
    const Sites s = sites_of_polygons(merge_polygons(in.second));
    per_site.push_back({in.first, row(in.first, s, runs) / double(s.sites.size())});
  }
  const Sites m = sites_of_polygons(merge_polygons(wires(40000, 4)));
  const double manhattan = row("generated wires (Manhattan, the reference)", m, runs) / double(m.sites.size());
  std::printf("\n| input | sweep a site | / Manhattan's |\n|---|---|---|\n");
  for (const auto& p : per_site) std::printf("| %s | %.2f us | %.2f |\n", p.first.c_str(), 1e6 * p.second, p.second / manhattan);
  std::printf("| generated wires (Manhattan) | %.2f us | 1.00 |\n", 1e6 * manhattan);
}

// The sweep tile by tile (tiles.hpp) against itself on the whole layer: automatic tiles on
// one and two threads (the scaling), and the whole layer's single sweep (what tiles cost).
void tiles_row(const std::string& name, const Sites& s, int runs) {
  const Box clip = clip_box(s);
  BuildOptions whole, one, two;
  whole.sweep = one.sweep = two.sweep = true;
  whole.tile_size = 0, whole.threads = 1;
  one.tile_size = two.tile_size = -1;
  one.threads = 1, two.threads = 2;
  double tw = 1e30, t1 = 1e30, t2 = 1e30;
  std::vector<Piece> pw, p1, p2;
  BuildStats st;
  for (int r = 0; r < runs; ++r) {
    tw = std::min(tw, seconds([&] { pw = build_pieces(s, clip, whole); }));
    t1 = std::min(t1, seconds([&] { p1 = build_pieces(s, clip, one, &st); }));
    t2 = std::min(t2, seconds([&] { p2 = build_pieces(s, clip, two); }));
  }
  auto same = [](const std::vector<Piece>& a, const std::vector<Piece>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i].a != b[i].a || a[i].b != b[i].b || a[i].p.x != b[i].p.x || a[i].p.y != b[i].p.y ||
          a[i].q.x != b[i].q.x || a[i].q.y != b[i].q.y)
        return false;
    return true;
  };
  std::printf("| %s | %zu | %zu (largest %zu sites) | %.3f s | %.3f s | %.3f s | %.2f | %.2f | %s |\n", name.c_str(),
              s.sites.size(), st.tiles, st.largest_tile_sites, tw, t1, t2, t1 / t2, tw / t2,
              same(pw, p1) && same(pw, p2) ? "yes" : "NO");
  std::fflush(stdout);
}

// The independent checker against the builds it checks, one thread each: the sampled check (the
// pipeline's default, kSampledSearchEvery) and the full one on the whole-layer sweep's pieces,
// over the sweep's and the subdivision's time for them (the subdivision only below 10^6 sites).
void check_row(const std::string& name, const Sites& s, int runs) {
  Diagram d;
  d.sites = s;
  d.clip = clip_box(s);
  BuildOptions sweep, sub;
  sweep.sweep = true, sweep.tile_size = 0, sweep.threads = 1;
  sub.threads = 1;
  const bool with_subdivision = s.sites.size() < 1000000;
  double tb = 1e30, tsub = 1e30, tc = 1e30, tf = 1e30;
  CheckOptions sampled, full;
  sampled.search_every = kSampledSearchEvery, full.search_every = 1;
  sampled.threads = full.threads = 1;
  bool ok = true;
  for (int r = 0; r < runs; ++r) {
    tb = std::min(tb, seconds([&] { d.pieces = build_pieces(s, d.clip, sweep); }));
    if (with_subdivision) tsub = std::min(tsub, seconds([&] { build_pieces(s, d.clip, sub); }));
    tc = std::min(tc, seconds([&] { ok = check_diagram(d, sampled).ok() && ok; }));
    tf = std::min(tf, seconds([&] { ok = check_diagram(d, full).ok() && ok; }));
  }
  if (with_subdivision)
    std::printf("| %s | %zu | %zu | %.3f s | %.3f s | %.3f s | %.3f s | %.2f | %.2f | %.2f | %s |\n", name.c_str(), s.sites.size(),
                d.pieces.size(), tb, tsub, tc, tf, tc / tb, tc / tsub, tf / tb, ok ? "yes" : "NO");
  else
    std::printf("| %s | %zu | %zu | %.3f s | — | %.3f s | %.3f s | %.2f | — | %.2f | %s |\n", name.c_str(), s.sites.size(),
                d.pieces.size(), tb, tc, tf, tc / tb, tf / tb, ok ? "yes" : "NO");
  std::fflush(stdout);
}

std::vector<Polygon> read_polygons(const char* path) {
  std::vector<Polygon> out;
  std::FILE* f = std::fopen(path, "r");
  if (!f) {
    std::fprintf(stderr, "cannot read %s\n", path);
    std::exit(2);
  }
  char kind;
  while (std::fscanf(f, " %c", &kind) == 1) {
    Ring ring;
    long long x, y;
    int c;
    while ((c = std::fgetc(f)) != EOF && c != '\n') {
      std::ungetc(c, f);
      if (std::fscanf(f, "%lld %lld", &x, &y) != 2) break;
      ring.push_back({x, y});
    }
    if (kind == 'o') out.push_back({ring, {}});
    else if (!out.empty()) out.back().holes.push_back(ring);
  }
  std::fclose(f);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 4 && std::string(argv[1]) == "memory") {  // bench_sweep memory WIRES TILE THREADS, under /usr/bin/time
    const Sites s = sites_of_polygons(merge_polygons(wires(std::strtoull(argv[2], nullptr, 10), 4)));
    BuildOptions o;
    o.sweep = true, o.tile_size = std::atof(argv[3]), o.threads = std::atoi(argv[4]);
    std::size_t n = 0;
    const double t = seconds([&] { n = build_pieces(s, clip_box(s), o).size(); });
    std::printf("%zu sites, tile %s, %d threads: %zu pieces in %.3f s\n", s.sites.size(), argv[3], o.threads, n, t);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "check") {  // bench_sweep check RUNS [NAME FILE ...]
    const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
    std::printf("| input | sites | pieces | sweep, 1 thread | subdivision, 1 thread | sampled check, 1 thread | full check, 1 thread | "
                "sampled / sweep | sampled / subdivision | full / sweep | passed |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 3; i + 1 < argc; i += 2) {
      const std::string file = argv[i + 1];
      check_row(argv[i], sites_of_polygons(merge_polygons(file.rfind("wires:", 0) == 0
                                                              ? wires(std::strtoull(file.c_str() + 6, nullptr, 10), 4)
                                                              : read_polygons(file.c_str()))),
                runs);
    }
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "wires") {  // bench_sweep wires RUNS N [N ...]: Boost and the sweep only
    const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
    std::printf("| input | points / segments | Boost.Polygon L2, 1 thread | sweep, 1 thread | subdivision, 1 thread | "
                "sweep / Boost | subdivision / sweep | same pieces |\n|---|---|---|---|---|---|---|---|\n");
    for (int i = 3; i < argc; ++i)
      row("generated wires", sites_of_polygons(merge_polygons(wires(std::strtoull(argv[i], nullptr, 10), 4))), runs, false);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "curved") {  // bench_sweep curved RUNS
    std::printf("| input | points / segments | Boost.Polygon L2, 1 thread | sweep, 1 thread | subdivision, 1 thread | "
                "sweep / Boost | subdivision / sweep | same pieces |\n|---|---|---|---|---|---|---|---|\n");
    curved(argc > 2 ? std::atoi(argv[2]) : 3);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "tiles") {  // bench_sweep tiles RUNS [NAME FILE ...]
    const int runs = argc > 2 ? std::atoi(argv[2]) : 3;
    std::printf("| input | sites | automatic tiles | whole layer, 1 thread | tiles, 1 thread | tiles, 2 threads | "
                "scaling 1 -> 2 threads | whole / tiles on 2 threads | same pieces |\n|---|---|---|---|---|---|---|---|---|\n");
    if (argc > 4) {
      for (int i = 3; i + 1 < argc; i += 2)
        tiles_row(argv[i], sites_of_polygons(merge_polygons(read_polygons(argv[i + 1]))), runs);
      return 0;
    }
    if (argc > 3) { tiles_row("generated wires", sites_of_polygons(merge_polygons(wires(std::atoi(argv[3]), 4))), runs); return 0; }
    tiles_row("generated wires, 10^5", sites_of_polygons(merge_polygons(wires(100000, 4))), runs);
    tiles_row("generated wires, 10^6", sites_of_polygons(merge_polygons(wires(1000000, 4))), runs);
    return 0;
  }
  const int runs = argc > 1 ? std::atoi(argv[1]) : 3;
  std::printf("| input | points / segments | Boost.Polygon L2, 1 thread | sweep, 1 thread | subdivision, 1 thread | "
              "sweep / Boost | subdivision / sweep | same pieces |\n|---|---|---|---|---|---|---|---|\n");
  if (argc > 3) {
    for (int i = 2; i + 1 < argc; i += 2)
      row(argv[i], sites_of_polygons(merge_polygons(read_polygons(argv[i + 1]))), runs);
    return 0;
  }
  const std::size_t most = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1000000;
  for (std::size_t n : {std::size_t(10000), std::size_t(100000), std::size_t(1000000)}) {
    if (n > most) break;
    row("random points, 2^20 square", sites_of_plain(random_points(n, 1 << 20, 1), {}), runs);
  }
  if (most >= 100000) row("random points on a 400 x 400 grid (ties)", sites_of_plain(random_points(100000, 400, 2), {}), runs);
  if (most >= 100000) row("wire corners as points", sites_of_plain(wire_corners(100000, 3), {}), runs);
  if (most >= 1000000) row("wire corners as points", sites_of_plain(wire_corners(1000000, 3), {}), runs);
  // The wires: 10^5 and 10^6 rectangles (the subdivision only on the smaller: minutes).
  if (most >= 100000) row("generated wires", sites_of_polygons(merge_polygons(wires(100000, 4))), runs);
  if (most >= 1000000) row("generated wires", sites_of_polygons(merge_polygons(wires(1000000, 4))), runs, false);
  // An octilinear layer: the same wires, each with a 45-degree jog.
  if (most >= 100000) row("generated wires with 45-degree jogs", sites_of_polygons(merge_polygons(bent_wires(100000, 4))), runs);
  return 0;
}
