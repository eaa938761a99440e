// libFuzzer target: random small polygon sets and segment sets through the core, with the
// independent checkers as the oracle. A diagram the checker rejects, a farthest diagram whose
// vertices are not at their weight, or any crash/sanitizer report is a finding.
//   built and run by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "linf/diagram.hpp"
#include "linf/farthest.hpp"

using namespace linf;

namespace {
struct Bytes {
  const std::uint8_t* p;
  std::size_t n, i = 0;
  int next() { return i < n ? p[i++] : 0; }
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes b{data, size};
  const int style = b.next() % 3;  // rectilinear, octilinear, any angle
  const int shapes = 1 + b.next() % 6;
  std::vector<Polygon> polys;
  std::vector<Segment> segs;
  for (int k = 0; k < shapes; ++k) {
    const Coord x = b.next(), y = b.next(), w = 1 + b.next() % 64, h = 1 + b.next() % 64;
    Polygon p;
    if (style == 0) {
      p.outer = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    } else if (style == 1) {
      const Coord c = std::min(w, h) / 3;
      p.outer = {{x + c, y}, {x + w, y}, {x + w, y + h - c}, {x + w - c, y + h}, {x, y + h}, {x, y + c}};
    } else {
      p.outer = {{x, y}, {x + w, y + b.next() % 16}, {x + w - b.next() % 16, y + h}, {x + b.next() % 8, y + h - 3}};
    }
    polys.push_back(p);
    segs.push_back({{x, y}, {x + Coord(b.next()) - 128, y + Coord(b.next()) - 128}});
  }
  try {
    Result r = voronoi_of_polygons(polys);  // throws DiagramError if the checker rejects it
    (void)r;
  } catch (const DiagramError& e) {
    std::fprintf(stderr, "checker rejected a diagram: %s\n", e.what());
    std::abort();
  } catch (const std::invalid_argument&) {
    // degenerate input the core refuses with a message: fine
  }
  std::vector<std::vector<Point>> sites;
  for (const Segment& s : segs) sites.push_back({s.a, s.b});
  const FarthestDiagram d = farthest_voronoi(segs);
  for (const FarthestVertex& v : d.vertices) {
    const double w = farthest_distance(sites, v.at);
    if (std::fabs(w - v.weight) > 1e-7 * (1 + w)) {
      std::fprintf(stderr, "farthest vertex at (%g, %g): weight %g, farthest distance %g\n", v.at.x, v.at.y, v.weight, w);
      std::abort();
    }
  }
  return 0;
}
