// One stage of a call's progress (linf/util/progress.hpp), stepped from many threads: parts
// are counted with an atomic, the watcher is told under a lock and at most every 0.1 s.
#pragma once
#include <atomic>
#include <chrono>
#include <mutex>

#include "linf/util/progress.hpp"

namespace linf::detail {

class ProgressMeter {
 public:
  ProgressMeter(const ProgressFn& fn, const char* stage, std::size_t total) : fn_(fn), stage_(stage), total_(total) {
    if (fn_) fn_(stage_, 0, total_), last_ = std::chrono::steady_clock::now();
  }

  void step(std::size_t parts = 1) {
    if (!fn_) return;
    const std::size_t done = done_ += parts;
    const auto now = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);  // busy: another thread tells
    if (!lock.owns_lock() || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    fn_(stage_, done, total_);
  }

 private:
  const ProgressFn& fn_;
  const char* stage_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace linf::detail
