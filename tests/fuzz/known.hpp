// Faults of the core that the fuzzer finds and that are not fixed yet. Until they are, an input
// showing one is counted and the counts are reported when the run ends ("known:" lines),
// instead of failing the run (LINF_FUZZ_STRICT=1 makes them findings). Delete a fault here once
// it is fixed.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include "diagram/affine.hpp"  // steep_edge: neither axis-parallel nor at 45 degrees
#include "linf/geometry/site.hpp"

namespace linf::fuzz::known {

enum Fault {
  None = -1,
  // The subdivision builder (the sweep's oracle) decides within an allowance of the distance
  // functions (1e-12 of the layer's box). Where two edges are nearly parallel (their
  // directions' sine below 1e-3, one of them neither axis-parallel nor at 45 degrees) the
  // bisector of their functions is placed only to that allowance over the functions'
  // difference of gradient, and a third site tied with both along a line (the diagonal through
  // their shared end) can then miss the tie test: the subdivision loses part of that piece, or
  // draws one along that line that is not there (an edge of two sites whose tie region begins
  // there; 2.4e-4 in the fuzzer's case). Its checker does not see it (the piece lies far from
  // the sites, where few of its random pairs fall, and within its tolerance of a tie); the
  // sweep has it right, and passes a full check.
  SubdivisionNearlyParallelEdges = 0,
  Count
};

inline const char* name(Fault f) {
  return f == SubdivisionNearlyParallelEdges ? "the subdivision at nearly parallel edges" : "none";
}

inline bool strict() {
  static const bool s = std::getenv("LINF_FUZZ_STRICT") && *std::getenv("LINF_FUZZ_STRICT") == '1';
  return s;
}

// Counts an input showing a known fault; the counts are printed when the process exits.
inline void count(Fault f) {
  static int counts[Count] = {};
  static const bool registered = [] {
    std::atexit([] {
      for (int i = 0; i < Count; ++i)
        if (counts[i] > 0) std::fprintf(stderr, "known: %s: %d inputs\n", name(Fault(i)), counts[i]);
    });
    return true;
  }();
  (void)registered;
  if (f > None && f < Count) ++counts[f];
}

// Which known fault may explain a diagram of these points and edges, built with or without
// the axis tie-break, failing its check: none.
inline Fault of_diagram(const std::vector<Point>& /*points*/, const std::vector<Segment>& /*edges*/,
                        bool /*axis_ties*/) {
  return None;
}

// Which known fault may explain the sweep and the subdivision disagreeing on a piece of the
// sites `owners` (sites S): SubdivisionNearlyParallelEdges if an owner is an edge nearly
// parallel to another edge of the layer (one of them steep: neither axis-parallel nor at 45
// degrees), or a point at the end of one.
inline Fault of_comparison(const SiteList& S, std::pair<int, int> owners) {
  auto nearly_parallel = [&](int i) {
    const Site& s = S[std::size_t(i)];
    if (s.is_point()) return false;
    const double ux = double(s.b.x - s.a.x), uy = double(s.b.y - s.a.y);
    for (const Site& t : S) {
      if (t.is_point() || (!linf::detail::steep_edge(s) && !linf::detail::steep_edge(t))) continue;
      const double vx = double(t.b.x - t.a.x), vy = double(t.b.y - t.a.y);
      const double sine = std::fabs(ux * vy - uy * vx) / (std::hypot(ux, uy) * std::hypot(vx, vy));
      if (sine > 0 && sine < 1e-3) return true;
    }
    return false;
  };
  for (int o : {owners.first, owners.second}) {
    if (o < 0 || std::size_t(o) >= S.size()) continue;
    const Site& s = S[std::size_t(o)];
    if (nearly_parallel(o)) return SubdivisionNearlyParallelEdges;
    if (s.is_point())
      for (int e : {s.end0, s.end1})
        if (e >= 0 && std::size_t(e) < S.size() && nearly_parallel(e)) return SubdivisionNearlyParallelEdges;
  }
  return None;
}

}  // namespace linf::fuzz::known
