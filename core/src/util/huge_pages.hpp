// Huge pages under a large reserved vector, asked for before its first touch.
//
// On the build machine a fresh 4 KB page costs a fault of several microseconds; writing the
// sweep's pieces into fresh memory took a fifth of the build in faults. Where transparent huge
// pages are on "madvise" (Debian's default), this makes the first touch fault once per 2 MB.
// Only the reserved capacity's whole 2 MB blocks are advised; untouched ones stay uncommitted.
//
// KLayout's process (and every process it starts) has transparent huge pages switched off as a
// whole (prctl PR_SET_THP_DISABLE), which overrides any advice: inside the editor and under
// `klayout -b` the sweep ran a fifth slower than in plain Python. Where the system's mode is
// "madvise", lifting that switch changes nothing but the regions that ask for huge pages (only
// ours do; KLayout asks for none), so it is lifted; under "always" it is left alone, as it then
// guards every allocation of the process.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>
#ifdef __linux__
#include <sys/mman.h>
#include <sys/prctl.h>
#endif

namespace linf {

// Whether a process-wide switch that overrides huge-page advice is off (lifting it where the
// mode is "madvise"); true off Linux, where there is none.
inline bool advised_huge_pages_allowed() {
#ifdef __linux__
  if (prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0) != 1) return true;
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(f, mode);
  if (mode.find("[madvise]") == std::string::npos) return false;
  return prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0) == 0;
#else
  return true;
#endif
}

template <typename T>
void huge_pages(std::vector<T>& v) {
#ifdef __linux__
  constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(v.data()) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(v.data() + v.capacity()) & ~(kHuge - 1);
  if (end > begin && advised_huge_pages_allowed()) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)v;
#endif
}

}  // namespace linf
