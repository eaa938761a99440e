// Printability of gauges (issue 34): each gauge's window simulated with the lithography model,
// its printed width read along its measurement line, pinches and bridges flagged, and a score
// that ranks the worst printing first (docs/design.md, "Lithography model", "Printability of
// gauges").
//
//   in:  the merged layer (flat arrays, DBU), the database unit in nm, the gauges as columns
//        (read in place, possibly strided: the gauge table's columns), optionally a context id
//        a gauge, and the model (kernels + threshold);
//   out: per gauge printed_cd (nm, NaN when not measured), fails (none / pinch / bridge) and
//        score, and the counts.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/litho/kernels.hpp"
#include "linf/util/strided.hpp"

namespace linf::litho {

// The gauge table's type codes: 1 (external) measures a space; 0 internal, 2 sandwich, 3 comb
// and 4 T measure a width (docs/design.md, "Gauge rules": their lines cross a feature).
constexpr std::int32_t kExternalGauge = 1;

struct GaugeColumns {
  Strided<double> cx, cy;          // the gauge point, DBU
  Strided<double> x1, y1, x2, y2;  // the measurement line's ends, DBU
  Strided<std::int32_t> type;      // the gauge table's codes (kExternalGauge: a space)
  Strided<double> cd;              // the drawn width or space, DBU
  // Optional (n = 0: none): gauges of one type with one id share one simulation, read once —
  // the plan's "one gauge with a count" (docs/design.md, "Gauge contexts").
  Strided<std::uint64_t> context;
  std::size_t size() const { return cx.size(); }
};

struct PrintModel {
  const Kernels* kernels = nullptr;  // period P nm; the window is P x P centred on the gauge point
  double threshold = 0;              // the resist threshold on the kernels' image scale
  // The process window (dose > 0): besides nominal dose and focus, two corners are read, as the
  // ICCAD 2013 contest pairs them: the inner one at dose 1 - dose with the `defocus` kernels (the
  // focus kernels when null: a dose-only window), the outer one at dose 1 + dose in focus. The
  // image scales with the dose squared, so a corner is the image against threshold / dose^2.
  // `defocus` must have the kernels' period and size. dose = 0: nominal only (no pv_band).
  const Kernels* defocus = nullptr;
  double dose = 0;
  // The resist's blur: every reading's image blurred along its line by a Gaussian of this
  // standard deviation (nm; LineProfile::blur). 0: a bare threshold on the aerial image.
  double blur = 0;
};

enum class Fail : std::uint8_t { none = 0, pinch = 1, bridge = 2 };

struct Printability {
  // Per gauge, in the input's order.
  std::vector<double> printed_cd;  // nm along the measurement line; NaN on a failure or when an
                                   // edge lies beyond the window's valid centre (P / 4 from the point)
  std::vector<Fail> fails;        // the worst over nominal and the corners (a width can only pinch,
                                  // a space only bridge)
  std::vector<Fail> fails_nominal;  // at nominal dose and focus
  // The width between the inner and the outer corner's crossings along the line, nm: |outer
  // width - inner width|, a failed corner's width 0; NaN without a process window or when an
  // edge lies beyond reach at a corner.
  std::vector<double> pv_band;
  // Lower = worse; the least over nominal and the corners of: measured, printed width / drawn
  // cd (> 0); pinch, I(c) / t - 1, bridge, t / I(c) - 1 (both in [-1, 0]: failures first, the
  // deeper the lower; I(c) the image at the gauge point, t that condition's threshold); no
  // edge within reach, 2 reach / drawn cd (a lower bound of the ratio).
  std::vector<double> score;
  std::size_t simulations = 0;  // gauges read on their own window (one a type and context)
  std::size_t shared = 0;       // gauges that took another gauge's reading (same type and context)
  std::size_t images = 0;       // line profiles computed: simulated gauges on one line share one
};

// Each simulated gauge's window is the square of side P (the kernels' period) centred on its
// point (exactly: the clip is held in half DBU, a gauge point being a midpoint of integer points);
// the layer's shapes are clipped to it (an edge crossing a side at an angle is cut at the
// nearest half DBU). The image is periodic, so only its valid
// centre, within P / 4 of the point, is read: the walk for the edges reaches P / 4 each way.
// `layer` must be merged (overlaps would count twice). `threads`: 0 for one per core; windows
// are independent. Throws std::invalid_argument with a sentence for a bad model (no kernels, a
// non-positive threshold or dbu), columns of different lengths, a gauge whose measurement line
// has no length or reaches outside its window, or a drawn cd that is not positive.
Printability printability(const FlatPolygons& layer, double dbu_nm, const GaugeColumns& gauges, const PrintModel& model,
                          int threads = 0);

// For each chunk of points, (cx, cy)[starts[c], starts[c + 1]), the layer's polygons (with
// their holes, in the layer's order) that meet the window of one of its points: everything
// printability() clips for gauges there, so that it reads a chunk's gauges on its part exactly
// as on the whole layer (the batch's Dask tasks). Flat arrays as FlatPolygons views them.
struct LayerPart {
  std::vector<std::int64_t> points, rings;
  FlatPolygons view() const { return {points.data(), points.size() / 2, rings.data(), rings.size()}; }
};
std::vector<LayerPart> window_shapes(const FlatPolygons& layer, double dbu_nm, double period, const Strided<double>& cx,
                                     const Strided<double>& cy, const std::vector<std::size_t>& starts);

// The aerial images of windows for pictures (the report's printed contours): for each centre
// (cx, cy) in DBU (on the half-DBU grid, as gauge points), the window of side P centred there
// exactly as printability() clips it, imaged on an m x m grid: values[k][j * m + i] is the image
// at the window's corner + (i, j) P / m, the corner being the centre minus P / 2; blurred by the
// resist's Gaussian `blur` (nm) in both directions (blur_grid). Throws std::invalid_argument for
// m below the kernels' size or the bad model input printability() refuses.
std::vector<std::vector<double>> window_images(const FlatPolygons& layer, double dbu_nm, const std::vector<double>& cx,
                                               const std::vector<double>& cy, const Kernels& kernels, int m,
                                               int threads = 0, double blur = 0);

}  // namespace linf::litho
