// Items made ahead, on a few threads, of the one thread that takes them in order: the makers'
// work overlaps the taker's, and at most `window` items are held at once. The tile jobs' plan
// (tiles.cpp): on a farm the submitting host's planning of a tile, one at a time, bounded how
// many workers could be kept busy.
#pragma once
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace linf::detail {

template <class T>
class Ahead {
 public:
  // make(worker, i) gives item i, worker < threads (for per-thread scratch). threads 0: each
  // item is made by take() itself, on the taker's thread.
  Ahead(std::size_t n, unsigned threads, std::size_t window, std::function<T(unsigned, std::size_t)> make)
      : n_(n), window_(std::max<std::size_t>(1, window)), make_(std::move(make)), slots_(window_) {
    try {
      for (unsigned w = 0; w < threads; ++w) makers_.emplace_back([this, w] { run(w); });
    } catch (const std::system_error&) {
      // No more threads to be had (EAGAIN): those there are make the items; none, take() does.
    }
  }
  ~Ahead() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    for (std::thread& t : makers_) t.join();
  }
  Ahead(const Ahead&) = delete;
  Ahead& operator=(const Ahead&) = delete;

  // The next item in order into `out`; false once all n were taken. An item whose making threw
  // throws here, in its turn: the error is the first failing item's, whatever the threads.
  bool take(T& out) {
    if (failed_) std::rethrow_exception(failed_);  // nothing after a failure is made
    if (taken_ == n_) return false;
    if (makers_.empty()) {
      try {
        out = make_(0, taken_++);
      } catch (...) {
        failed_ = std::current_exception();
        throw;
      }
      return true;
    }
    std::unique_lock<std::mutex> lock(m_);
    Slot& s = slots_[taken_ % window_];
    cv_.wait(lock, [&] { return s.ready; });
    ++taken_;
    s.ready = false;
    cv_.notify_all();
    if (s.error) std::rethrow_exception(failed_ = std::exchange(s.error, nullptr));
    out = std::move(s.item);
    s.item = T();
    return true;
  }

 private:
  struct Slot {
    bool ready = false;
    T item{};
    std::exception_ptr error;
  };

  void run(unsigned w) {
    for (;;) {
      std::size_t i;
      {
        std::unique_lock<std::mutex> lock(m_);
        // Item i goes to slot i % window once item i - window was taken.
        cv_.wait(lock, [&] { return stop_ || claimed_ == n_ || claimed_ < taken_ + window_; });
        if (stop_ || claimed_ == n_) return;
        i = claimed_++;
      }
      Slot made;
      made.ready = true;
      try {
        made.item = make_(w, i);
      } catch (...) {
        made.error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(m_);
        // After a failure nothing more is claimed: the items before it are still made, so
        // take() reaches the failure in order.
        if (made.error) stop_ = true;
        slots_[i % window_] = std::move(made);
      }
      cv_.notify_all();
    }
  }

  const std::size_t n_, window_;
  const std::function<T(unsigned, std::size_t)> make_;
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<Slot> slots_;
  std::size_t claimed_ = 0;  // under m_
  std::size_t taken_ = 0;    // written by the taker under m_ (read alone by it outside)
  std::exception_ptr failed_;  // the taker's alone
  bool stop_ = false;
  std::vector<std::thread> makers_;  // last: started once the rest is ready
};

}  // namespace linf::detail
