// A gauge's neighbouring space: the plan's strata and plot read a width next to the space beside
// it (docs/design.md, "Split rules").
//
//   in:  every gauge's point, cd and type (plain data: SpacePoint), the gauges asked about, a
//        radius (DBU, L-infinity);
//   out: for each gauge asked about, the least cd among the other kind's gauges whose points lie
//        within the radius of its point, NaN where there is none. The other kind: for a width
//        gauge (internal, sandwich, comb, T: their cd is a width) the external gauges; for an
//        external gauge the internal ones.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/gauges/gauge.hpp"

namespace linf {

struct SpacePoint {
  double x = 0, y = 0, cd = 0;
  GaugeType type = GaugeType::Internal;
};

// Throws std::invalid_argument for a radius that is not positive and finite or an index out of
// range. `threads`: 0 for one per core; the result does not depend on it.
std::vector<double> neighbouring_spaces(const std::vector<SpacePoint>& gauges, const std::vector<std::int32_t>& asked,
                                        double radius, int threads = 0);

}  // namespace linf
