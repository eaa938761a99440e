// Items made ahead on a few threads, taken in order (util/ahead.hpp, the tile jobs' plan): every
// item once and in order, never more than the window ahead of the taker, and an item whose making
// threw throws in its turn, the first failing one's error whatever the threads.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "util/ahead.hpp"

using linf::detail::Ahead;

TEST(Ahead, EveryItemOnceInOrderWithinTheWindow) {
  for (unsigned threads : {0u, 1u, 2u, 4u})
    for (std::size_t window : {1u, 3u, 8u}) {
      const std::size_t n = 200;
      std::atomic<std::size_t> taken{0}, worst{0};
      std::atomic<unsigned> bad_worker{0};
      Ahead<std::string> ahead(n, threads, window, [&](unsigned w, std::size_t i) {
        if (threads > 0 && w >= threads) ++bad_worker;
        // How far ahead of the taker this item is made: at most the window (its slot frees
        // only once item i - window is taken).
        const std::size_t t = taken.load();
        if (i >= t) worst = std::max(worst.load(), i - t);
        if (i % 17 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));  // out of turn
        return std::to_string(i);
      });
      std::string item;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_TRUE(ahead.take(item)) << threads << " threads, window " << window << ", item " << i;
        ASSERT_EQ(item, std::to_string(i)) << threads << " threads, window " << window;
        ++taken;
      }
      EXPECT_FALSE(ahead.take(item));
      EXPECT_FALSE(ahead.take(item));
      EXPECT_EQ(bad_worker.load(), 0u);
      if (threads > 0) EXPECT_LE(worst.load(), window) << threads << " threads, window " << window;
    }
}

TEST(Ahead, TheFirstFailingItemThrowsInItsTurn) {
  for (unsigned threads : {0u, 1u, 3u}) {
    Ahead<int> ahead(100, threads, 6, [](unsigned, std::size_t i) {
      if (i == 40) std::this_thread::sleep_for(std::chrono::milliseconds(20));  // 41 fails first in time
      if (i == 40 || i == 41) throw std::runtime_error("item " + std::to_string(i));
      return int(i);
    });
    int item = -1;
    for (int i = 0; i < 40; ++i) {
      ASSERT_TRUE(ahead.take(item)) << threads << " threads";
      ASSERT_EQ(item, i) << threads << " threads";
    }
    try {
      ahead.take(item);
      ADD_FAILURE() << threads << " threads: item 40 did not throw";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "item 40") << threads << " threads";
    }
    // Nothing after a failure: taking again throws the same error, it never waits.
    EXPECT_THROW(ahead.take(item), std::runtime_error) << threads << " threads";
  }
}

TEST(Ahead, LeftEarlyItStopsItsThreads) {
  std::atomic<std::size_t> made{0};
  {
    Ahead<int> ahead(1000000, 3, 4, [&](unsigned, std::size_t i) {
      ++made;
      return int(i);
    });
    int item;
    ASSERT_TRUE(ahead.take(item));
    ASSERT_TRUE(ahead.take(item));
  }  // the destructor joins the makers; a hang here fails the test by its time-out
  EXPECT_LE(made.load(), 2u + 4u);  // the two taken and a window's
}
