// The resist threshold rule (issue 34): the threshold at which the layer's dominant line, at its
// typical pitch, prints at its drawn width (docs/design.md, "Lithography model").
#pragma once
#include "linf/litho/kernels.hpp"

namespace linf::litho {

struct Calibration {
  double threshold = 0;  // the image at the drawn line's edges
  double pitch = 0;      // the pitch used: period / round(period / pitch), so the grating is periodic in the window
  double contrast = 0;   // (I_line - I_space) / (I_line + I_space) at the line's and the space's middles
};

// Endless lines of `width` nm at `pitch` nm (rounded to the nearest pitch that divides the
// kernels' period), at nominal dose and focus: the threshold is the image at their drawn edges.
// Throws std::invalid_argument when 0 < width < pitch <= period does not hold, or when the
// model does not resolve the grating: at doses 0.98 and 1.02 (the image times 0.98^2, 1.02^2)
// the line's middle must stay above the threshold and the space's below, and the profile must
// cross it once on each side of the line, at the drawn edges. blur: the resist's Gaussian blur
// (standard deviation, nm) on the image across the lines, as the gauges are read.
Calibration calibrate_threshold(const Kernels& kernels, double width, double pitch, double blur = 0);

}  // namespace linf::litho
