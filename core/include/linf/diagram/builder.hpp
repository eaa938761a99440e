// The diagram builder: adaptive subdivision of the clip box, local lower envelopes.
//
// A box keeps the sites that can be nearest somewhere in it (lower bound of the distance over
// the box <= the least upper bound among all sites; inside a group sharing one affine L-inf
// function over the box, the same test in L1). When few remain, the box is cut into convex
// cells where every remaining distance function is affine; there the regions are half-plane
// intersections and their edges, split where the owner across changes, are the Voronoi
// pieces. Arithmetic is double with explicit rounding allowances; the checker (checker.hpp)
// is what vouches for the result. The top-level boxes are shared out to worker threads.
//
// Ownership rule (the 1-dimensionalisation of two-dimensional L-inf bisectors): a point belongs
// to the site with the least L-inf distance; ties go to the least L1 distance, then to a point
// site over a segment site, then to the lower site index. Hence two points on a horizontal line
// are split by their perpendicular bisector, and an axis-parallel edge and its endpoint by the
// perpendicular through the endpoint, as in CGAL's convention.
#pragma once
#include <any>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"
#include "linf/util/progress.hpp"

namespace linf {

struct BuildOptions {
  int local_sites = 16;       // solve a box directly once at most this many sites remain,
  int affine_sites = 48;     // or at most this many of which
  int bent_sites = 6;         // at most this many are not affine over the box,
  int crowded_sites = 160;    // or at most this many when quartering would not thin them out
  int paired_sites = 16;      // in solves of at most this many sites, each is a dominance reference
  bool axis_ties = true;      // the L1 tie-break of points and axis-parallel edges as a half-plane
                              // (off: by their L1 pieces, as between any sites; the same pieces)
  double min_box = 1.0 / 64;  // never cut a box below this side (DBU)
  int threads = 0;            // workers; 0: one per hardware thread
  bool far_field_pass = true; // build beyond the sites' bounding box in a second pass with the
                              // border's owners only (off: one pass over the clip box)
  double tile_size = 0;       // DBU; > 0: build the sites' box tile by tile, holding one tile's
                              // sites at a time (same pieces for every size; see tiles.hpp);
                              // < 0: automatic, at most 2^15 sites of its own in the fullest tile
  bool sweep = false;         // build with the sweep-line builder (sweep.hpp): each tile's sites
                              // swept at once, a tile a thread; only for sites it handles
                              // (sweep_handles), and not with a TileRunner
};

struct BuildStats {
  std::size_t boxes = 0, solves = 0, solved_sites = 0, cells = 0, raw_pieces = 0;
  std::size_t solved_pairs = 0;  // the local solves' sizes squared, summed: their cost grows so
  std::size_t tie_cells = 0;     // cells cut by L1 pieces for the tie-break
  std::size_t envelopes = 0;     // region edges along which the L1 profiles' envelope was walked
  std::size_t owners_evaluated = 0;  // parts of region edges whose owner beyond took every tied
                                    // site's functions (Model::owner_beyond, not axis_owner)
  std::size_t tiles = 0, tasks = 0, largest_tile_sites = 0;
};

// Straight pieces with owners and clearances; kinds are left for the classifier.
// Pieces of one edge are joined where they continue each other in a straight line.
std::vector<Piece> build_pieces(const Sites& sites, const Box& clip, const BuildOptions& opt = {},
                               BuildStats* stats = nullptr, const ProgressFn& progress = {});

// The order build_pieces leaves its pieces in: owner pair, then position.
bool join_order(const Piece& x, const Piece& y);
// How build_pieces joins pieces across parts: one owner pair's pieces, sorted by join_order,
// joined where they continue each other in a straight line; in place, in join_order.
void join_pair(std::vector<Piece>& pieces);

// A part of the diagram: one tile's pieces (global site ids, joined within the part, sorted
// by owner pair as join_pieces leaves them) and the box they lie in. Pieces continuing each
// other across parts are not joined; a vertex on a part's box may have pieces in several parts.
// The sink may take the part's contents; left in place, its buffer serves the next part.
using PartSink = std::function<void(std::vector<Piece>& part, const Box& frame)>;

// The same pieces as build_pieces, handed over part by part as the tiles are built instead of
// kept: joining the parts (join_pieces over their union) gives build_pieces' result.
void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartSink& sink);

// Builds the tiles elsewhere (another process, another host): takes the tiles' jobs one at a
// time from `next` (false when none is left), has each built by build_tile_job, and hands the
// results to `done` in the order the jobs were taken (a view, read during the call: a result
// is megabytes, and is not copied). A job holds only its own tile's sites and halo, never the
// layer's. Exceptions thrown by `done` must reach the caller.
using TileRunner = std::function<void(const std::function<bool(std::string& job)>& next,
                                      const std::function<void(std::string_view result)>& done)>;

// build_parts with the tiles built by `runner` (if empty, as build_parts): the same parts in
// the same order, bit for bit. The far field (the second pass) is built here. `progress` is
// told of the tasks built (tiled: of the tiles' tasks, or of the runner's tiles), then of the
// far field's.
void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartSink& sink, const TileRunner& runner, const ProgressFn& progress = {});

// A sink's work on a part that depends on the part alone (classifying its pieces, reading its
// vertices): the sweep's tiles run it on the thread that swept the tile, as soon as it is swept,
// several tiles at once and in any order; elsewhere it runs just before the sink. What it
// returns reaches the sink with the part.
using PartPrepare = std::function<std::any(std::vector<Piece>& part, const Box& frame)>;
using PreparedSink = std::function<void(std::vector<Piece>& part, const Box& frame, std::any& prepared)>;

// build_parts with a prepare step: the same parts in the same order, each prepared once.
// remote (0: none): with a runner and the sweep, a tag every tile job carries, asking its task
// to prepare the part itself (a preparation the pipeline defines: pipeline/tile_task.hpp); a
// result that comes with its preparation's bytes reaches the sink with them as a std::string
// in `prepared`, and `prepare` is not called on it.
void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartPrepare& prepare, const PreparedSink& sink, const TileRunner& runner,
                 const ProgressFn& progress = {}, std::uint32_t remote = 0);

// One tile job's result bytes from its bytes, with `threads` workers (0: one a core): the
// same bytes on every host and for every thread count. Throws std::invalid_argument for bytes
// that are not a job of this core.
std::string build_tile_job(std::string_view job, int threads);

}  // namespace linf
