// The same stretches in the same order, to the last bit: owners, kind, length, every path point
// and clearance (gtest assertions; the first difference stops the comparison).
#pragma once
#include <gtest/gtest.h>

#include "linf/gauges/stretch.hpp"

namespace linf::testing {

inline void expect_same(const Stretch& a, const Stretch& b) {
  ASSERT_EQ(a.a, b.a);
  ASSERT_EQ(a.b, b.b);
  ASSERT_EQ(a.kind, b.kind);
  ASSERT_EQ(a.length, b.length);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    ASSERT_EQ(a.path[k].x, b.path[k].x);
    ASSERT_EQ(a.path[k].y, b.path[k].y);
    ASSERT_EQ(a.clearance[k], b.clearance[k]);
  }
}

inline void expect_same(const Stretches& want, const Stretches& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    expect_same(want[i], got[i]);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace linf::testing
