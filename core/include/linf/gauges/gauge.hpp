// Gauges: where a CD-SEM measurement should be taken, scored and ranked (thesis 5.1).
//
//   in:  a Diagram
//   out: every gauge candidate of the layer, ranked: rank 1 is the most likely pinch or bridge.
//
// The rules where the thesis leaves a choice open are in docs/design.md, "Gauge rules".
#pragma once
#include <cstdint>
#include <vector>

#include "linf/util/paged.hpp"
#include "linf/geometry/piece.hpp"
#include "linf/gauges/stretch.hpp"

namespace linf {

enum class GaugeType : std::uint8_t { Internal, External, Sandwich, Comb, T };

const char* gauge_type_name(GaugeType t);

// One gauge. Held by the million on a full layer, so only what cannot be derived is kept: the
// measurement line comes from the two sites (measurement_line), the rank from the position in
// Gauges::gauges and the normalised score from Gauges::top_score.
struct Gauge {
  Vec2 at;               // the gauge point, on the diagram
  double cd = 0;         // the critical dimension measured: twice the L-inf clearance at `at`
  double score = 0;      // lower = more critical
  double tiebreak = 0;   // extension (internal, external) or overlap (sandwich, comb, T)
  std::int32_t a = -1, b = -1;     // the two measured sites
  std::int32_t stretch = -1;       // the stretch the gauge sits on
  std::int32_t neighbour = -1;     // sandwich/comb/T: the critical neighbour's external stretch
  std::int32_t teeth = 0;          // comb/T: teeth on the critical side
  GaugeType type = GaugeType::Internal;
};

// The measurement line: across the two measured features as a CD-SEM measures them. Along
// the axis on which the L-inf square about the gauge point touches them on opposite sides (so
// cd long where both are edges across it), ending on their boundary; between two slanted edges,
// their points nearest (Euclidean) the gauge point. The rule: docs/design.md, "Gauge rules".
struct MeasurementLine {
  Vec2 p, q;
};

struct GaugeOptions {
  // A neighbour is a tooth when the feature it shows the base (a line end, a narrow side, a
  // corner) is at most this fraction of the base's edge long: it meets part of the base only.
  double tooth_fraction = 0.5;
  // Spaces wider than this many typical widths (the extension-weighted median width of the
  // layer) are the far field between blocks and around the layout, not pattern: no external
  // gauge there, and such a space makes no neighbour for sandwich, comb or T. 0 keeps all.
  double space_limit_widths = 10;
  // Threads placing the gauges (0: one per core); the gauges do not depend on it.
  int threads = 0;
};

struct Gauges {
  Stretches stretches;        // those the gauges lie on (Gauge::stretch, Gauge::neighbour)
  std::size_t measurable = 0; // the measurable stretches considered (see gauges_of)
  Paged<Gauge> gauges;        // ranked: gauges[i] has rank i + 1, the most critical first (a
                              // mapped file: a full layer has tens of millions)
  double top_score = 0;       // the highest score among them
  double typical_width = 0;   // extension-weighted median width of the internal gauges
  double space_limit = 0;     // widest space reported (infinite if no limit)

  // score / the highest score among the gauges returned (0 if every score is 0).
  double norm_score(const Gauge& g) const { return top_score > 0 ? g.score / top_score : 0.0; }
};

MeasurementLine measurement_line(const Sites& sites, const Gauge& g);

Gauges gauges_of(const Diagram& d, const GaugeOptions& opt = {});

// The owner pairs whose stretches the gauges are made from: not adjacent, facing each other.
bool measurable_pair(const Sites& sites, std::int32_t a, std::int32_t b, PieceKind kind);

// The same in two steps, so that a caller can let the diagram's pieces go in between (on a
// large layer they are the largest thing in memory): the stretches the gauges are made from
// (measurable pairs only), then the gauges. take_gauge_stretches consumes d.pieces.
Stretches gauge_stretches(const Diagram& d);
Stretches take_gauge_stretches(Diagram& d);
Gauges gauges_of(const Sites& sites, Stretches stretches, const GaugeOptions& opt = {});

}  // namespace linf
