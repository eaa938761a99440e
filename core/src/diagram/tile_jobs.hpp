// Tile jobs: one tile of the tiled pass (tiles.hpp) as plain data, built anywhere.
//
// A job holds only its tile's sites (its own and its halo's, ascending global ids, layout
// coordinates), the tile's task boxes with each task's halo (local ids), and what the whole
// layer fixes: the origin, the root box, tau and the build options. A sweep's job
// (opt.sweep) holds the sites sweep_tiled gives its tile, its frame in layout coordinates and
// no tasks; its result is sweep_part's, in layout coordinates. Built from the job alone
// (build_tile_job), a tile gives bit for bit the pieces it gives in the local pass: the model
// sees the same sites in the same order, shifted by the same origin, with the same tau. A job
// may also ask its task to prepare the pieces as the host's sink would (`prepare`, a tag the
// pipeline defines: pipeline/tile_task.hpp); the result then carries that as opaque bytes.
//
// The bytes are the structs' own (native, little-endian on every supported host) behind a
// header that names the format and the structs' sizes: every host must run the same core.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "linf/diagram/builder.hpp"

namespace linf::detail {

struct TileJob {
  BuildOptions opt;
  Point origin;
  Box root, frame;  // builder coordinates (relative to origin)
  double tau = 0;
  std::vector<int> ids;     // global ids, ascending
  std::vector<Site> sites;  // sites[i] is global site ids[i]
  std::vector<Box> tasks;   // builder coordinates
  std::vector<std::vector<int>> halos;  // per task, local ids (into sites)
  // What the task prepares beside the pieces (build_parts' `remote`; 0 nothing), and then the
  // ring neighbours (end0, end1) of its point sites that are not among its sites, global ids
  // ascending: a piece's kind and sides are told from its owners and their neighbours.
  std::uint32_t prepare = 0;
  std::vector<int> near_ids;
  std::vector<Site> near;
};

struct TileResult {
  Box frame;                  // builder coordinates
  std::vector<Piece> pieces;  // builder coordinates, global ids, joined within the tile
  BuildStats stats;           // the tile's work counts (tiles, tasks, largest tile included)
  std::string prepared;       // the job's preparation (opaque here), empty if none
};

std::string encode_job(const TileJob& job);
TileJob decode_job(std::string_view bytes);  // throws std::invalid_argument if not a job
std::string encode_result(const TileResult& r);
TileResult decode_result(std::string_view bytes);

// The tile's pieces from the job alone, `threads` workers (0: one a core).
TileResult build_job(const TileJob& job, int threads);

}  // namespace linf::detail
