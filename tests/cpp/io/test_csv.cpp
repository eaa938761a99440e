// The CSV writers: the number format, and a plan's context columns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "linf/io/csv.hpp"
#include "linf/io/gauge_table.hpp"

using namespace linf;

// The CSV files' numbers are printf's "%.6f" (which the Python writer's bytes are compared
// with in the KLayout tests); the writer's own conversion must give the same text for every
// double, near-halves and signs included.
TEST(Csv, FixedSixAsPrintf) {
  std::mt19937_64 rng(11);
  std::vector<double> xs{0.0, -0.0, 1e-7, -1e-7, 4e-7, 5e-7, 6e-7, -5e-7, 0.0000015, 0.0000025, 2.5e-7, 999999.9999995,
                         1e9 - 0.0000005, 1e9, 1e12 + 0.5, -1e15, 1e300, INFINITY, -INFINITY, NAN};
  std::uniform_int_distribution<std::int64_t> coord(-(std::int64_t(1) << 31), std::int64_t(1) << 31);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 300000; ++i) {
    const std::int64_t k = coord(rng);
    xs.push_back(double(k) * 0.0025);                      // a site coordinate in micrometres
    xs.push_back(double(k) * 0.001 + unit(rng) * 1e-3);    // a piece's end
    xs.push_back((double(k) + 0.5) / 1e6);                 // near a half in the sixth place
    xs.push_back(std::ldexp(unit(rng) - 0.5, int(coord(rng) % 40)));
  }
  int differ = 0;
  for (double x : xs) {
    char want[512];
    std::snprintf(want, sizeof want, "%.6f", x);
    std::string got;
    linf::append_fixed6(got, x);
    if (got != want && ++differ <= 5) ADD_FAILURE() << x << ": " << got << " instead of " << want;
  }
  EXPECT_EQ(differ, 0);
}

namespace {
std::string read_all(const std::string& path) {
  std::string out;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
    std::fclose(f);
  }
  return out;
}
}  // namespace

// A plan's gauge lists: the lines of gauges.csv followed by the context id (16 hex digits,
// leading zeros kept) and the count; without contexts, the same bytes as before.
TEST(Csv, GaugeRowsWithContexts) {
  const double reals[2 * kGaugeReals] = {0, 0, 10, 0, 5, 0, 10, 10, 0.5, 3,
                                         1, 2, 1, 8, 1, 5, 6, 4.8, 0.25, 1};
  std::int32_t ints[2 * kGaugeInts] = {};
  ints[0] = 1, ints[12] = 1;                          // rank 1, external
  ints[kGaugeInts] = 2, ints[kGaugeInts + 12] = 2;    // rank 2, sandwich
  const GaugeTableView table{reals, ints, 2};
  const std::string plain = ::testing::TempDir() + "linf_rows_plain.csv";
  const std::string with = ::testing::TempDir() + "linf_rows_context.csv";
  write_gauges_csv_rows(table, {1, 0}, 0.001, plain);
  const GaugeContexts contexts{{0x00ab, 0xfedcba9876543210ull}, {3, 1}};
  write_gauges_csv_rows(table, {1, 0}, 0.001, with, &contexts);
  const std::string a = read_all(plain), b = read_all(with);
  EXPECT_EQ(a,
            "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank\r\n"
            "2,sandwich,0.001000,0.002000,0.001000,0.008000,0.001000,0.005000,0.006000,0.004800,0.250000,0.001000,2\r\n"
            "1,external,0.000000,0.000000,0.010000,0.000000,0.005000,0.000000,0.010000,0.010000,0.500000,0.003000,1\r\n");
  EXPECT_EQ(b,
            "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank,context,count\r\n"
            "2,sandwich,0.001000,0.002000,0.001000,0.008000,0.001000,0.005000,0.006000,0.004800,0.250000,0.001000,2,"
            "00000000000000ab,3\r\n"
            "1,external,0.000000,0.000000,0.010000,0.000000,0.005000,0.000000,0.010000,0.010000,0.500000,0.003000,1,"
            "fedcba9876543210,1\r\n");
  const GaugeContexts short_of_rows{{1}, {1}};
  EXPECT_THROW(write_gauges_csv_rows(table, {1, 0}, 0.001, with, &short_of_rows), std::invalid_argument);
  std::remove(plain.c_str());
  std::remove(with.c_str());
}
