// The threshold rule: endless lines of the drawn width at the pitch print at their width with
// the threshold found, for the file kernels and both optics presets; bad or unresolved
// gratings are errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/litho/calibration.hpp"
#include "linf/litho/optics.hpp"
#include "linf/litho/resist.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf;
using namespace linf::litho;

namespace {

// The printed width of the middle line of an endless grating (integer nm coordinates), read
// with `threshold`, as a gauge would: across the line through its middle.
Cut printed(const Kernels& k, int width, int pitch, double threshold) {
  const Coord period = Coord(k.period);
  std::vector<Polygon> lines;
  for (Coord c = pitch / 2; c < period; c += pitch) lines.push_back(litho_test::box(c - width / 2, 0, c - width / 2 + width, period));
  const AerialImage im(k, MaskSpectrum(lines, Window{}, k.period, k.half()));
  const double middle = (period / pitch / 2) * pitch + pitch / 2 - width / 2 + width / 2.0;
  return measure(LineProfile(im, middle, 100, 1, 0), threshold, Across::printed, pitch);
}

std::string error_of(const Kernels& k, double w, double p) {
  try {
    calibrate_threshold(k, w, p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Calibration, DominantLinePrintsAtItsDrawnWidth) {
  struct Case {
    const char* model;
    int width, pitch;
  };
  const Kernels duv = kernels_from_optics(optics_preset("duv193")), euv = kernels_from_optics(optics_preset("euv"));
  for (const Case& c : {Case{"iccad13", 100, 256}, Case{"iccad13", 160, 512}, Case{"duv193", 64, 128}, Case{"duv193", 50, 128},
                        Case{"euv", 16, 32}, Case{"euv", 20, 64}}) {
    const Kernels& k = std::string(c.model) == "iccad13" ? litho_test::focus() : std::string(c.model) == "duv193" ? duv : euv;
    const Calibration cal = calibrate_threshold(k, c.width, c.pitch);
    EXPECT_EQ(cal.pitch, double(c.pitch));  // the pitch divides the period: used as it is
    const Cut cut = printed(k, c.width, c.pitch, cal.threshold);
    ASSERT_EQ(cut.outcome, Cut::Outcome::measured) << c.model;
    EXPECT_NEAR(cut.width, c.width, 1e-5) << c.model << " " << c.width << "/" << c.pitch;
    // A line 4 nm wider prints wider, one 4 nm narrower narrower, with the same threshold.
    EXPECT_GT(printed(k, c.width + 4, c.pitch, cal.threshold).width, c.width + 1.0);
    const Cut narrower = printed(k, c.width - 4, c.pitch, cal.threshold);
    EXPECT_TRUE(narrower.outcome == Cut::Outcome::pinch || narrower.width < c.width - 1.0);
    std::printf("[ litho ] %s: lines %d nm at pitch %d nm print at their width with threshold %.4f (contrast %.3f)\n", c.model,
                c.width, c.pitch, cal.threshold, cal.contrast);
  }
  // A pitch that does not divide the period is rounded to one that does: 500 -> 512.
  EXPECT_EQ(calibrate_threshold(litho_test::focus(), 160, 500).pitch, 512.0);
}

// With the resist's blur the lines still print at their drawn width, read with the blur, at a
// threshold of their own; the blur lowers the grating's contrast; a negative blur is refused.
TEST(Calibration, BlurredLinesPrintAtTheirDrawnWidth) {
  const Kernels euv = kernels_from_optics(optics_preset("euv"));
  const Calibration bare = calibrate_threshold(euv, 22, 64), blurred = calibrate_threshold(euv, 22, 64, 5);
  EXPECT_LT(blurred.contrast, bare.contrast - 0.02);
  const Coord period = Coord(euv.period);
  std::vector<Polygon> lines;
  for (Coord c = 32; c < period; c += 64) lines.push_back(litho_test::box(c - 11, 0, c + 11, period));
  const AerialImage im(euv, MaskSpectrum(lines, Window{}, euv.period, euv.half()));
  LineProfile across(im, 4 * 64 + 32, 100, 1, 0);
  across.blur(5);
  const Cut cut = measure(across, blurred.threshold, Across::printed, 64);
  ASSERT_EQ(cut.outcome, Cut::Outcome::measured);
  EXPECT_NEAR(cut.width, 22, 1e-5);
  EXPECT_THROW(calibrate_threshold(euv, 22, 64, -1), std::invalid_argument);
}

TEST(Calibration, BadOrUnresolvedGratingsAreErrors) {
  const Kernels& k = litho_test::focus();
  EXPECT_EQ(error_of(k, 0, 128), "threshold calibration: a line of 0 nm at a pitch of 128 nm; the width must be positive "
                                 "and below the pitch, the pitch at most the period (2048 nm)");
  EXPECT_NE(error_of(k, 128, 128).find("the width must be positive and below the pitch"), std::string::npos);
  EXPECT_NE(error_of(k, 100, 4096).find("the pitch at most the period"), std::string::npos);
  // iccad13 does not resolve a 128 nm pitch (its image is flat within 1%).
  EXPECT_NE(error_of(k, 64, 128).find("threshold calibration: the model does not resolve lines of 64 nm at a pitch of 128 nm"),
            std::string::npos)
      << error_of(k, 64, 128);
}
