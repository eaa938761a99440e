// The worker pool: every job runs once, and a job's exception reaches the caller once every
// thread has ended (under a memory limit, std::bad_alloc in a tile used to abort the process).
#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <stdexcept>
#include <vector>

#include "util/parallel.hpp"

using linf::detail::parallel_for;

TEST(Parallel, EveryJobOnce) {
  std::vector<std::atomic<int>> done(1000);
  parallel_for(done.size(), 2, [&](unsigned, std::size_t i) { ++done[i]; });
  for (const auto& d : done) EXPECT_EQ(d.load(), 1);
}

TEST(Parallel, AJobsExceptionReachesTheCaller) {
  for (int threads : {1, 2, 3}) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallel_for(200, threads,
                              [&](unsigned, std::size_t i) {
                                ++ran;
                                if (i == 7) throw std::bad_alloc();
                              }),
                 std::bad_alloc)
        << threads << " threads";
    EXPECT_GE(ran.load(), 8) << threads << " threads";
    // Every worker throws: still one exception, still no abort.
    EXPECT_THROW(parallel_for(50, threads, [](unsigned, std::size_t) { throw std::runtime_error("x"); }),
                 std::runtime_error);
  }
}
