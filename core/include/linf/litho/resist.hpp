// A threshold resist and the printed width along a measurement line.
//
// The resist prints where the aerial image is at least the threshold (the mask's polygons are
// the transmitting parts, as in the ICCAD 2013 model: a drawn line prints where it is bright).
// A width is read where the band-limited image crosses the threshold along the line, by
// bracketing and root finding on the image itself, not on pixels.
#pragma once
#include "linf/litho/image.hpp"

namespace linf::litho {

// The ICCAD 2013 contest's threshold (its `TargetDensity`): on the image of its kernels, whose
// clear field is 0.9536 in focus (Kernels::clear_field), not 1.
constexpr double kIccad13Threshold = 0.225;

// What a measurement line crosses: a feature that should print (an internal gauge: a width) or
// a gap that should stay clear (an external gauge: a space).
enum class Across { printed, clear };

struct Cut {
  enum class Outcome {
    measured,  // both edges found: width = hi - lo
    pinch,     // a feature that does not print at the line's point: no crossing, width 0
    bridge,    // a gap that prints through at the line's point: width 0
    open,      // no edge within `reach` on a side (that side's crossing is +-reach)
  };
  Outcome outcome = Outcome::measured;
  double width = 0;      // hi - lo, nm
  double lo = 0, hi = 0;  // where the edges are, nm along the line from its point (lo <= 0 <= hi)
};

// Walks from t = 0 both ways in steps of `step` nm until the image crosses `threshold` (or
// |t| passes `reach`), then finds the crossing to 1e-6 nm. The image's frequencies reach 2h / P
// on each axis (h = the kernels' half), so along a line 2h sqrt(2) / P: a shortest period of
// 42.6 nm for iccad13, 26.8 nm for duv193, 7.9 nm for euv. A 2 nm step, at most a quarter of it, cannot
// step over two crossings except near a tangency.
Cut measure(const LineProfile& line, double threshold, Across what, double reach, double step = 2.0);

}  // namespace linf::litho
