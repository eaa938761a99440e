// Tiles: the builder's pass over the sites' box, cut so that a layer of millions of shapes
// never holds every site's distance functions at once.
//
// The box is cut into a fixed grid of tasks: the quadtree boxes of one level, chosen from the
// site count only. Each task gathers the sites that can own a point of it (its halo: every site
// within the task's least upper bound U of the distance, grown until nothing nearer is left
// out) and is subdivided from there exactly as without tiles. Tiles are square groups of
// tasks of the requested size; one tile's sites and distance functions are in memory at a
// time, its tasks run on the worker threads. Since no task depends on how the tasks are
// grouped, the pieces are bit-identical for every tile size (tested).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "util/parallel.hpp"
#include "subdivision.hpp"

namespace linf::detail {

// Pieces (global site ids, joined within each tile, not across tiles) of the diagram inside
// `root`, handed to `sink` tile by tile with the tile's box. Boxes and pieces are relative to
// `origin` (bounds.hpp, shifted); the sites are not. `progress` is told of the tasks built.
void build_tiled(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt, double tau,
                 BuildStats& st, const PartSink& sink, const ProgressFn& progress = {});

// The same parts in the same order, each tile built by `runner` from a job (tile_jobs.hpp)
// holding only the tile's sites: planned and gathered here, built wherever the runner sends it.
// `prepare` (0: none) goes into every job, with its point sites' ring neighbours; the sink gets
// each result's preparation bytes with its part (empty where the task prepared nothing).
using JobSink = std::function<void(std::vector<Piece>& part, const Box& frame, std::string& prepared)>;
void build_tiled_jobs(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt,
                      double tau, BuildStats& st, const JobSink& sink, const TileRunner& runner,
                      const ProgressFn& progress = {}, std::uint32_t prepare = 0);

// The same tiles built by the sweep-line builder (opt.sweep): a tile's sites, the union of its
// tasks' halos and every segment's end sites, swept at once and cut to the tile's frame; as
// many tiles swept side by side as there are threads, each prepared (`prepare`, if set) on the
// thread that swept it, handed to `sink` one at a time and in order. Pieces and frames in layout
// coordinates (the frames, dyadic, shift exactly), so the sweep's vertices reach the sink as it
// computed them. With `far`, also the far field beside the tiles: the pieces within `clip` and
// outside `root` (far_field.hpp), from the sites nearest at a point of root's border, found by
// the walk that finds a tile's halo; left in *far for the caller to hand over last.
void sweep_tiled(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt, double tau,
                 BuildStats& st, const PartPrepare& prepare, const PreparedSink& sink, const ProgressFn& progress = {},
                 const Box* clip = nullptr, std::vector<Piece>* far = nullptr);

}  // namespace linf::detail
