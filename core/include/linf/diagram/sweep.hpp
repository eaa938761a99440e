// The sweep-line builder of the L-inf Voronoi diagram: Fortune's sweep as Boost.Polygon's
// voronoi_builder runs it, with the predicates of our ownership rule (builder.hpp) decided
// exactly. O(n log n). Same output as build_pieces: straight pieces with their owners and end
// clearances, joined per owner pair, clipped to `clip`; kinds are left for the classifier.
//
// It takes points and axis-parallel segments (every Manhattan layer); sweep_handles says
// whether it takes a layer's sites. One thread, the whole layer at once (no tiles). The
// subdivision builder (build_pieces) stays the default and the oracle it is checked by.
#pragma once
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

struct SweepStats {
  std::size_t site_events = 0, vertices = 0, edges = 0;
};

bool sweep_handles(const Sites& sites);

// Throws std::invalid_argument for sites it does not handle.
std::vector<Piece> sweep_pieces(const Sites& sites, const Box& clip, SweepStats* stats = nullptr);

}  // namespace linf
