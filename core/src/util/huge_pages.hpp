// Huge pages under a large reserved vector, asked for before its first touch.
//
// On the build machine a fresh 4 KB page costs a fault of several microseconds; writing the
// sweep's pieces into fresh memory took a fifth of the build in faults. Where transparent huge
// pages are on "madvise" (Debian's default), this makes the first touch fault once per 2 MB.
// Only the reserved capacity's whole 2 MB blocks are advised; untouched ones stay uncommitted.
#pragma once
#include <cstdint>
#include <vector>
#ifdef __linux__
#include <sys/mman.h>
#endif

namespace linf {

template <typename T>
void huge_pages(std::vector<T>& v) {
#ifdef __linux__
  constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(v.data()) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(v.data() + v.capacity()) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)v;
#endif
}

}  // namespace linf
