// Paged<T>: the whole-layer arrays kept in a mapped temporary file (linf/paged.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "linf/util/paged.hpp"

namespace {
using linf::Paged;

// kB of the process's anonymous and file-backed resident memory (Linux).
std::pair<long, long> resident() {
  std::ifstream f("/proc/self/status");
  std::string key;
  long anon = -1, file = -1;
  while (f >> key) {
    if (key == "RssAnon:") f >> anon;
    else if (key == "RssFile:") f >> file;
  }
  return {anon, file};
}

TEST(Paged, GrowsKeepsAndShrinksLikeAVector) {
  // Past kFileFrom bytes the array moves from anonymous memory into its file: what was
  // written before stays.
  const long n = long(Paged<long>::kFileFrom / sizeof(long)) + 100000;
  Paged<long> a;
  EXPECT_TRUE(a.empty());
  for (long i = 0; i < n; ++i) a.push_back(i * i);
  ASSERT_EQ(a.size(), std::size_t(n));
  for (long i = 0; i < n; i += 997) ASSERT_EQ(a[std::size_t(i)], i * i);
  EXPECT_EQ(a.back(), (n - 1) * (n - 1));
  a.resize(10);  // shrinks the file: what is kept stays
  EXPECT_EQ(a.size(), 10u);
  EXPECT_LT(a.capacity(), 100000u);
  EXPECT_EQ(a[9], 81);
  a.resize(20);  // grows with zeros
  EXPECT_EQ(a[9], 81);
  EXPECT_EQ(a[19], 0);
  Paged<long> c = a;  // copies
  c[9] = 7;
  EXPECT_EQ(a[9], 81);
  EXPECT_EQ(c.size(), 20u);
  Paged<long> b = std::move(a);  // moves the mapping
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(b[9], 81);
  a = std::move(b);
  EXPECT_EQ(a[9], 81);
  long sum = 0;
  for (long v : a) sum += v;
  EXPECT_EQ(sum, 285);  // 0 + 1 + ... + 81
  a.clear();
  EXPECT_TRUE(a.empty());
}

TEST(Paged, PagesAreTheFilesNotTheProcesss) {
  // 64 MB written into a Paged array are file pages (the kernel may write them out and drop
  // them), not anonymous memory the process must hold.
  const auto before = resident();
  ASSERT_GE(before.first, 0);
  Paged<double> a;
  const std::size_t n = (std::size_t(64) << 20) / sizeof(double);
  a.reserve(n);
  for (std::size_t i = 0; i < n; ++i) a.push_back(double(i));
  const auto after = resident();
  EXPECT_LT(after.first - before.first, 8 * 1024) << "anonymous kB grew";
  EXPECT_GT(after.second - before.second, 48 * 1024) << "file-backed kB grew";
  EXPECT_EQ(a[n - 1], double(n - 1));
}

TEST(Paged, NoPlaceForTheFileIsAnError) {
  const char* old = std::getenv("TMPDIR");
  const std::string keep = old ? old : "";
  setenv("TMPDIR", "/nonexistent/linf_opc", 1);
  Paged<int> small;
  small.push_back(1);  // below kFileFrom: no file needed
  EXPECT_EQ(small[0], 1);
  Paged<int> a;
  EXPECT_THROW(a.reserve(Paged<int>::kFileFrom / sizeof(int) + 1), std::runtime_error);
  if (old) setenv("TMPDIR", keep.c_str(), 1);
  else unsetenv("TMPDIR");
}

}  // namespace
