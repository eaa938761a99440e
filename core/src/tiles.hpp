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
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

#include "subdivision.hpp"

namespace linf::detail {

// Pieces (global site ids, not yet joined) of the diagram inside `root`.
std::vector<Piece> build_tiled(const std::vector<Site>& sites, const Box& root, const BuildOptions& opt, double tau,
                               BuildStats& st);

// Worker threads for n jobs: `threads`, or one per core if 0, at most n.
inline unsigned worker_count(std::size_t n, int threads) {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  return unsigned(std::max<std::size_t>(1, std::min<std::size_t>(threads > 0 ? unsigned(threads) : hw, n)));
}

// Calls job(worker, i) for i in [0, n) on `threads` threads (0: one per core); worker < threads.
inline void parallel_for(std::size_t n, int threads, const std::function<void(unsigned, std::size_t)>& job) {
  const unsigned k = worker_count(n, threads);
  std::atomic<std::size_t> next{0};
  auto work = [&](unsigned w) {
    for (std::size_t i; (i = next++) < n;) job(w, i);
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < k; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& t : pool) t.join();
}

}  // namespace linf::detail
