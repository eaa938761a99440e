// Thousands of seeded random small layouts, every one checked by the independent checker and
// by the piece-end oracle (tests/fuzz/ends_check.hpp: no piece ends while its edge goes on).
#include <gtest/gtest.h>

#include <chrono>

#include "../fuzz/ends_check.hpp"
#include "layouts.hpp"
#include "linf/diagram/diagram.hpp"

using namespace linf;
using linf::testing::Style;

namespace {
void run_style(Style style, int count, int shapes) {
  int failures = 0;
  std::size_t pieces = 0, points = 0, separated = 0, judged = 0;
  const auto t0 = std::chrono::steady_clock::now();
  DiagramOptions opt;
  opt.checker.crossing_pairs = 300;
  for (int seed = 1; seed <= count; ++seed) {
    try {
      Result r = voronoi_of_polygons(linf::testing::random_layout(std::uint64_t(seed), style, shapes), opt);
      pieces += r.diagram.pieces.size();
      points += r.check.sampled_points;
      separated += r.check.pairs_separated;
      const linf::fuzz::EndsReport e = linf::fuzz::check_piece_ends(r.diagram);
      judged += e.judged;
      if (!e.failure.empty() && ++failures <= 5) ADD_FAILURE() << "seed " << seed << ": " << e.failure;
    } catch (const DiagramError& e) {
      if (++failures <= 5) ADD_FAILURE() << "seed " << seed << ": " << e.what();
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[random] style %d: %d layouts, %zu pieces, %zu points sampled, %zu separated pairs, %zu piece ends "
              "judged, %.2f s\n", int(style), count, pieces, points, separated, judged, s);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(separated, std::size_t(count));  // the completeness test really ran
  EXPECT_GT(judged, std::size_t(count));     // and the piece-end oracle
}
}  // namespace

TEST(RandomLayouts, Rectilinear) { run_style(Style::Rectilinear, 1000, 6); }
TEST(RandomLayouts, Octilinear) { run_style(Style::Octilinear, 1000, 6); }
TEST(RandomLayouts, AnyAngle) { run_style(Style::AnyAngle, 1000, 5); }
