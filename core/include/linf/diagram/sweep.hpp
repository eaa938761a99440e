// The sweep-line builder of the L-inf Voronoi diagram: Fortune's sweep as Boost.Polygon's
// voronoi_builder runs it, with the predicates of our ownership rule (builder.hpp) decided
// exactly. O(n log n). Same output as build_pieces: straight pieces with their owners and end
// clearances, joined per owner pair, clipped to `clip`; kinds are left for the classifier.
//
// It takes points and non-crossing segments of any slope (sweep_handles says so for every
// layer; it stays for callers that ask). sweep_pieces builds the whole layer in one thread;
// build_pieces with BuildOptions::sweep builds it tile by tile with sweep_part, a tile a
// thread. The batch and the editor build with it; the core's own default stays the subdivision
// builder, the oracle it is checked by.
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

// A part of a diagram, for tiles (tiles.hpp): the diagram of the sites `ids` (ascending, with
// every segment's end sites) inside `frame` and outside `*hole` if given, with the ids of
// `sites`. Within the frame it is the whole layer's diagram when every site that can own a
// point there is among `ids` (a tile's halo).
std::vector<Piece> sweep_part(const SiteList& sites, const std::vector<int>& ids, const Box& frame,
                              const Box* hole = nullptr);

// The same part from the sites `ids` alone (subset[k] is site ids[k], its segment ends still
// global ids): what a tile job carries (tile_jobs.hpp). The same pieces as sweep_part.
std::vector<Piece> sweep_subset(const std::vector<Site>& subset, const std::vector<int>& ids, const Box& frame);

}  // namespace linf
