// A tile task on another host: a tile job built, and its pieces prepared as the stream's sink
// prepares them (pipeline/stream.cpp), so that the submitting host only merges.
//
//   in:  a tile job's bytes (build_parts with a runner, builder.hpp), the builder's threads
//   out: its result's bytes: build_tile_job's, and where the job asks for kGaugeReadings, the
//        pieces classified and their vertices read for the gauges' stretches (StretchStream::
//        read_bytes with measurable_pair), from the job's sites and their ring neighbours alone.
//
// The job's sites are numbered locally for the reading (global ids ascending, so every order by
// id is kept) and the reading's ids turned back into the layer's: the same kinds and the same
// reading, bit for bit, as the host's (tested).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace linf {

// The preparation stream_voronoi asks of a sweep's tile jobs when its stretches take the
// measurable pairs (StreamOutputs::keep_measurable).
constexpr std::uint32_t kGaugeReadings = 1;

std::string run_tile_job(std::string_view job, int threads);

}  // namespace linf
