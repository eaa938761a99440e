// A minimal worker pool: jobs 0..n-1 taken in turn by a few threads. Shared by the builder's
// tiles and the checker (which shares no geometry with the builder, only this); and the split
// that lets two threads sort (and join) the two halves of one array.
#pragma once
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace linf::detail {

// Worker threads for n jobs: `threads`, or one per core if 0, at most n.
inline unsigned worker_count(std::size_t n, int threads) {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  return unsigned(std::max<std::size_t>(1, std::min<std::size_t>(threads > 0 ? unsigned(threads) : hw, n)));
}

// Calls job(worker, i) for i in [0, n) on `threads` threads (0: one per core); worker < threads.
// The first exception a job throws (std::bad_alloc under a memory limit, say) stops the others
// from taking new jobs and is rethrown here once every thread has ended: an exception leaving a
// thread, or a thread left unjoined, would abort the process instead of reporting it.
inline void parallel_for(std::size_t n, int threads, const std::function<void(unsigned, std::size_t)>& job) {
  const unsigned k = worker_count(n, threads);
  std::atomic<std::size_t> next{0};
  std::mutex failed_mutex;
  std::exception_ptr failed;
  auto work = [&](unsigned w) {
    try {
      for (std::size_t i; (i = next++) < n;) job(w, i);
    } catch (...) {
      next = n;
      std::lock_guard<std::mutex> lock(failed_mutex);
      if (!failed) failed = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned w = 1; w < k; ++w) pool.emplace_back(work, w);
  } catch (const std::system_error&) {
    // No more threads to be had (EAGAIN): the jobs run on those there are.
  }
  work(0);
  for (auto& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

// Reorders [first, last) so that the elements `less` than a pivot (the median of about 1,024
// evenly spaced ones) come first, and returns where the others begin: two parts of about half
// each, with elements equal under `less` all on one side, that sort side by side into the one
// sort's order. At least 1,024 elements.
template <class T, class Less>
T* split_at_sampled_median(T* first, T* last, Less less) {
  const std::size_t n = std::size_t(last - first);
  std::vector<T> sample;
  sample.reserve(1025);
  for (std::size_t i = 0; i < n; i += n / 1024) sample.push_back(first[i]);
  std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(sample.size() / 2), sample.end(), less);
  const T pivot = sample[sample.size() / 2];
  return std::partition(first, last, [&](const T& x) { return less(x, pivot); });
}

}  // namespace linf::detail
