// Faults of the core that the fuzzer finds and that are not fixed yet. Until they are, an input
// showing one is counted and the counts are reported when the run ends, instead of failing the
// run (LINF_FUZZ_STRICT=1 makes them findings). Delete a fault here once it is fixed. None is
// known now: every failure is a finding.
#pragma once
#include <cstdlib>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::fuzz::known {

enum Fault { None = -1 };

inline bool strict() {
  static const bool s = std::getenv("LINF_FUZZ_STRICT") && *std::getenv("LINF_FUZZ_STRICT") == '1';
  return s;
}

// Counts an input showing a known fault (none is known: never called with one).
inline void count(Fault) {}

// Which known fault may explain a diagram of these points and edges, built with or without
// the axis tie-break, failing its check: none.
inline Fault of_diagram(const std::vector<Point>& /*points*/, const std::vector<Segment>& /*edges*/,
                        bool /*axis_ties*/) {
  return None;
}

}  // namespace linf::fuzz::known
