#include "linf/pipeline/tile_task.hpp"

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "diagram/tile_jobs.hpp"
#include "linf/diagram/classify.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/gauges/stretch.hpp"

namespace linf {

namespace {

// The job's sites, then their neighbours, numbered from 0 (local site i < n is the layer's
// job.ids[i]); an end (end0, end1) that is in neither gets a number of its own past those, never
// looked up (adjacent() only compares it), so that two sites name the same end exactly when they
// do in the layer.
Sites local_sites(const detail::TileJob& job) {
  Sites l;
  std::unordered_map<int, std::int32_t> extra;
  const std::int32_t n = std::int32_t(job.ids.size()), m = std::int32_t(job.near_ids.size());
  auto local = [&](std::int32_t g) -> std::int32_t {
    if (g < 0) return g;
    auto it = std::lower_bound(job.ids.begin(), job.ids.end(), g);
    if (it != job.ids.end() && *it == g) return std::int32_t(it - job.ids.begin());
    it = std::lower_bound(job.near_ids.begin(), job.near_ids.end(), g);
    if (it != job.near_ids.end() && *it == g) return n + std::int32_t(it - job.near_ids.begin());
    return extra.emplace(g, n + m + std::int32_t(extra.size())).first->second;
  };
  l.sites.reserve(std::size_t(n + m));
  for (const auto* list : {&job.sites, &job.near})
    for (Site s : *list) {
      s.end0 = local(s.end0), s.end1 = local(s.end1);
      l.sites.push_back(s);
    }
  return l;
}

}  // namespace

std::string run_tile_job(std::string_view bytes, int threads) {
  const detail::TileJob job = detail::decode_job(bytes);
  detail::TileResult res = detail::build_job(job, threads);
  if (job.prepare == kGaugeReadings && job.opt.sweep && !res.pieces.empty()) {
    const Sites sites = local_sites(job);
    std::vector<Piece> part = res.pieces;
    const auto to_local = [&](std::int32_t g) {
      return std::int32_t(std::lower_bound(job.ids.begin(), job.ids.end(), g) - job.ids.begin());
    };
    for (std::size_t i = 0; i < part.size(); ++i) {
      part[i].a = to_local(part[i].a), part[i].b = to_local(part[i].b);
      part[i].kind = classify(sites, part[i]);
      res.pieces[i].kind = part[i].kind;
    }
    const StretchStream reader(sites, [&sites](std::int32_t a, std::int32_t b, PieceKind k) {
      return measurable_pair(sites, a, b, k);
    });
    res.prepared = reader.read_bytes(part, res.frame, job.ids);
  }
  return detail::encode_result(res);
}

}  // namespace linf
