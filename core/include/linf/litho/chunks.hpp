// Which gauges simulate, and how they are cut into chunks of nearby points for tasks elsewhere
// (the batch's Dask workers; docs/design.md, "The printability elsewhere").
//
//   in:  per gauge its point (DBU), its type code and optionally its context id; the height of a
//        band (DBU) and the number of chunks wanted;
//   out: the simulating gauges in chunk order, the chunks' starts, and per gauge where the reading
//        it takes sits in that order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "linf/util/strided.hpp"

namespace linf::litho {

// Who simulates: the first gauge of each (type, context) in the table's order; the others read
// its result. Without contexts (context.size() == 0) every gauge simulates.
struct Sources {
  std::vector<std::size_t> source;  // per gauge, the gauge whose reading it takes
  std::vector<std::size_t> reps;    // the simulating gauges, ascending
};
Sources sources_of(const Strided<std::int32_t>& type, const Strided<std::uint64_t>& context);

// A chunk holds kMinChunk to kMaxChunk simulating gauges (about reps / wanted), more only to
// keep every gauge of one point together (one line, one image: the images count stays the
// local one). The rule: the simulating gauges sorted by band (floor(cy / band)), then cx, cy and
// number; cut every `size` of them, each cut moved on past gauges on the previous one's point;
// each chunk's gauges ascending by number, so a chunk reads them in the table's order.
constexpr std::size_t kMinChunk = 256, kMaxChunk = 8192;
struct Chunks {
  std::vector<std::size_t> gauges;  // the simulating gauges, chunk after chunk
  std::vector<std::size_t> starts;  // chunk c is gauges[starts[c], starts[c + 1])
  std::vector<std::size_t> at;      // per gauge, where its source's reading is in `gauges`
};
Chunks plan_chunks(const Strided<double>& cx, const Strided<double>& cy, const Strided<std::int32_t>& type,
                   const Strided<std::uint64_t>& context, double band, std::size_t wanted);

}  // namespace linf::litho
