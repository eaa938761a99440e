// The threshold rule (calibration.hpp): read the image of an endless grating at its drawn edge.
#include "linf/litho/calibration.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "linf/litho/image.hpp"
#include "linf/litho/mask.hpp"
#include "linf/litho/resist.hpp"

namespace linf::litho {

Calibration calibrate_threshold(const Kernels& kernels, double width, double pitch, double blur) {
  const double period = kernels.period;
  if (!(width > 0) || !(pitch > width) || !(pitch <= period)) {
    std::ostringstream s;
    s << "threshold calibration: a line of " << width << " nm at a pitch of " << pitch
      << " nm; the width must be positive and below the pitch, the pitch at most the period (" << period << " nm)";
    throw std::invalid_argument(s.str());
  }
  Calibration c;
  const int lines = std::max(1, int(std::lround(period / pitch)));
  c.pitch = period / lines;
  if (!(width < c.pitch)) throw std::invalid_argument("threshold calibration: the width must be below the pitch used");
  // Lines across the whole window (endless with the period), centred on (j + 1/2) pitch;
  // coordinates in picometres so that any width and pitch fit to 1 pm.
  const double pm = 1e-3;
  std::vector<Polygon> grating;
  const Coord top = Coord(std::llround(period / pm));
  for (int j = 0; j < lines; ++j) {
    const double centre = (j + 0.5) * c.pitch;
    const Coord x0 = Coord(std::llround((centre - width / 2) / pm)), x1 = Coord(std::llround((centre + width / 2) / pm));
    grating.push_back(Polygon{{{x0, 0}, {x1, 0}, {x1, top}, {x0, top}}, {}});
  }
  const AerialImage image(kernels, MaskSpectrum(grating, Window{{0, 0}, pm}, period, kernels.half()));
  const double centre = 0.5 * c.pitch;
  LineProfile across(image, centre, 0.5 * period, 1, 0);
  across.blur(blur);
  c.threshold = across.at(width / 2);
  const double line = across.at(0), space = across.at(c.pitch / 2);
  c.contrast = (line - space) / (line + space);
  // The threshold must cut the profile once on each side, at the drawn edges.
  const Cut cut = measure(across, c.threshold, Across::printed, c.pitch / 2);
  // Resolved means more than a ripple: line and space still on their sides of the threshold
  // at the contest's dose window, +-2% (the image scales with the dose squared).
  const double low = 0.98 * 0.98, high = 1.02 * 1.02;
  if (!(line * low > c.threshold && c.threshold > space * high) || cut.outcome != Cut::Outcome::measured ||
      std::abs(cut.width - width) > 1e-3) {
    std::ostringstream s;
    s << "threshold calibration: the model does not resolve lines of " << width << " nm at a pitch of " << c.pitch
      << " nm (image " << line << " in the line, " << c.threshold << " at its edge, " << space << " in the space)";
    throw std::invalid_argument(s.str());
  }
  return c;
}

}  // namespace linf::litho
