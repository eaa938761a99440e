// util/huge_pages.hpp: a process that has transparent huge pages switched off as a whole (as
// KLayout's is, and every process it starts) gets them back for advised regions where the
// system's mode is "madvise", and keeps the switch under any other mode.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "util/huge_pages.hpp"

#ifdef __linux__
TEST(HugePages, ProcessSwitchLiftedWhereOnlyAdvisedRegionsGetThem) {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  if (!std::getline(f, mode)) GTEST_SKIP() << "no transparent huge pages on this system";
  const int before = prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0);
  ASSERT_EQ(prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0), 0);
  ASSERT_EQ(prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), 1);
  std::vector<double> v;
  v.reserve(std::size_t(1) << 20);  // 8 MB: whole 2 MB blocks to advise
  linf::huge_pages(v);
  const bool madvise = mode.find("[madvise]") != std::string::npos;
  EXPECT_EQ(prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), madvise ? 0 : 1) << "mode: " << mode;
  prctl(PR_SET_THP_DISABLE, before == 1 ? 1 : 0, 0, 0, 0);
}
#endif
