// Giving memory back to the system from the middle of a live buffer: a large layer's pieces
// are consumed front to back while the stretches are built from them, and the buffer can only
// be freed whole at the end. The pages inside [begin, end) are returned (Linux: they read as
// zero afterwards, so the caller must never read that range again); elsewhere nothing happens.
#pragma once
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace linf::detail {

inline void release_pages(const void* begin, const void* end) {
#if defined(__linux__)
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t lo = (std::uintptr_t(begin) + page - 1) / page * page;
  const std::uintptr_t hi = std::uintptr_t(end) / page * page;
  if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);
#else
  (void)begin, (void)end;
#endif
}

}  // namespace linf::detail
