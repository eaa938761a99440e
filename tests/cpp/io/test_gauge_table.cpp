// The gauge table's rows: the same bytes whether they are made on one thread or several, in
// memory or through the file's batches, and the same as one gauge at a time.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/diagram/diagram.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/io/gauge_table.hpp"
#include "layouts.hpp"

using namespace linf;

namespace {

// A layer with more gauges than a file batch (2^14 rows) and a block of rows (2^12), and a
// count that is a multiple of neither.
const Result& layer() {
  static const Result r = voronoi_of_polygons(linf::testing::block(7, linf::testing::Style::Octilinear, 20, 20));
  return r;
}

// The two column blocks, reals then ints, as the file holds them.
std::string in_memory(int threads, const std::function<void(const Gauge&)>& each = {}) {
  Gauges g = gauges_of(layer().diagram);
  const std::size_t n = g.gauges.size();
  std::string reals(kGaugeRealBytes * n, '\0'), ints(kGaugeIntBytes * n, '\0');
  GaugeTableWriter table(n, reals.data(), ints.data());
  write_gauge_table(layer().diagram.sites, g, table, each, threads);
  return reals + ints;
}

std::string in_file(int threads) {
  Gauges g = gauges_of(layer().diagram);
  const std::string path = ::testing::TempDir() + "linf_gauge_table_" + std::to_string(threads);
  GaugeTableWriter table(g.gauges.size(), path);
  write_gauge_table(layer().diagram.sites, g, table, {}, threads);
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::remove(path.c_str());
  return bytes;
}

}  // namespace

TEST(GaugeTable, RowsDoNotDependOnTheThreadsOrTheWay) {
  const std::size_t n = gauges_of(layer().diagram).gauges.size();
  ASSERT_GT(n, std::size_t(1) << 14);
  ASSERT_NE(n % (std::size_t(1) << 12), 0u);
  // One gauge at a time, through the callback: the rows as they were always made.
  std::size_t seen = 0;
  const std::string one = in_memory(3, [&](const Gauge&) { ++seen; });
  EXPECT_EQ(seen, n);
  ASSERT_EQ(one.size(), (kGaugeRealBytes + kGaugeIntBytes) * n);
  // The ranks are 1..n in order: every row was written where it belongs.
  const std::int32_t* ints = reinterpret_cast<const std::int32_t*>(one.data() + kGaugeRealBytes * n);
  for (std::size_t i = 0; i < n; i += 997) ASSERT_EQ(ints[i * kGaugeInts], std::int32_t(i + 1));
  // Compared whole, without printing megabytes when they differ.
  EXPECT_TRUE(in_memory(1) == one);
  EXPECT_TRUE(in_memory(3) == one);
  EXPECT_TRUE(in_file(1) == one);
  EXPECT_TRUE(in_file(3) == one);
}

TEST(GaugeTable, ACoordinateBeyond32BitsFailsOnAnyThread) {
  // Sites far beyond 32 bits: the first gauge's row cannot be written, whichever thread makes it.
  Sites far = layer().diagram.sites;
  for (Site& s : far.sites) s.a.x += Coord(1) << 40, s.b.x += Coord(1) << 40;
  for (int threads : {1, 3}) {
    Gauges g = gauges_of(layer().diagram);
    const std::size_t n = g.gauges.size();
    std::vector<char> reals(kGaugeRealBytes * n), ints(kGaugeIntBytes * n);
    GaugeTableWriter table(n, reals.data(), ints.data());
    EXPECT_THROW(write_gauge_table(far, g, table, {}, threads), std::range_error) << threads;
  }
}
