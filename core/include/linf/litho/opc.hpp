// An emulated model-based OPC (docs/design.md, "OPC before the reading"): the layer's edges cut
// into fragments and moved along their normals until the model prints each fragment's middle at
// its drawn edge. Printability then reads the layer as it prints after an OPC, as a process-window
// check of a real flow does, instead of the drawn target, whose bias an OPC would remove.
//
//   in:  the merged layer (flat arrays, DBU), the database unit in nm, the model (kernels,
//        threshold, resist blur) and the layer's typical width (nm), which bounds the moves;
//   out: the corrected layer (flat arrays in quarter DBU: the same polygons in the same order,
//        each ring rebuilt from its moved fragments) and how far it converged.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/litho/kernels.hpp"

namespace linf::litho {

struct OpcModel {
  const Kernels* kernels = nullptr;  // the reading's own kernels: the window is their period
  double threshold = 0;              // the resist threshold the reading uses
  double blur = 0;                   // the resist's blur (nm), along each fragment's normal
};

struct OpcRules {
  double width = 0;  // nm, the layer's typical width: the moves' bounds
  int iterations = 6;
  double feedback = 0.4;  // the share of a fragment's edge placement error it moves an iteration
};

// The corrected layer's grid: its points are in DBU / kOpcScale, so that moves are not rounded
// to the DBU (a 1 nm step of a 22 nm EUV line's edge moves its printed edge by about 2 nm).
constexpr std::int64_t kOpcScale = 4;

struct OpcResult {
  std::vector<std::int64_t> points;  // x, y pairs, in DBU / scale
  std::int64_t scale = kOpcScale;
  std::vector<std::int64_t> rings;   // as FlatPolygons: an outer ring's count > 0, a hole's < 0
  std::size_t fragments = 0;
  std::size_t kept = 0;  // polygons left as drawn: an edge off the axes
  // The edge placement error over all fragments (nm), read before each iteration's move and after
  // the last: iterations + 1 values each.
  std::vector<double> rms_epe, max_epe;
  FlatPolygons view() const { return {points.data(), points.size() / 2, rings.data(), rings.size()}; }
};

// Rules (docs/design.md, "OPC before the reading"):
// - Fragments about the model's resolution long: an axis-parallel edge of length L is cut into
//   max(1, round(L / r)) of equal length (ends on the quarter-DBU grid), r = the period / the
//   kernels' half size, about lambda / (NA (1 + sigma_out)) for a preset (22.3 nm for euv).
// - Fragments of a tile whose reading lines coincide (the two edges of a wire are cut alike, line
//   ends sit on one track) are read on one profile of the image.
// - A fragment's error is read on the image along its outward normal through its middle, blurred
//   by the resist: e = (I - t) / -dI/dn (the printed edge lies e beyond the drawn one);
//   +-width / 10 where the image has no falling edge there; never more than the width.
// - Every iteration reads all fragments on the same mask, then moves each by -g e, at most
//   width / 10, its total move within [-width / 4, +width / 2]; g starts at `feedback` and halves
//   each time the fragment's error changes sign.
// - The mask is rebuilt with the moves rounded to a quarter DBU: jogs between fragments, corners
//   where the moved lines of two edges meet. Polygons with an edge off the axes stay as drawn.
// - The image is read in tiles of half the kernels' period, each inside a window of the period
//   centred on it. The result does not depend on `threads` (0: one per core).
// Throws std::invalid_argument with a sentence for a bad model or rules or a malformed layer.
OpcResult correct_mask(const FlatPolygons& layer, double dbu_nm, const OpcModel& model, const OpcRules& rules,
                       int threads = 0);

}  // namespace linf::litho
