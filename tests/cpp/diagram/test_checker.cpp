// The checker's sampled mode (CheckOptions::search_every): which pieces it searches for a closer
// site, and that it still rejects a diagram built without some of its sites. The checker's
// other rejections are in test_reproducers.cpp.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "layouts.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/geometry/sites.hpp"

using namespace linf;

namespace {
CheckReport check(const Diagram& d, int every, int threads) {
  CheckOptions o;
  o.search_every = every;
  o.threads = threads;
  return check_diagram(d, o);
}

// Wires of varied lengths and offsets, 20 DBU apart.
std::vector<Segment> wires(int n) {
  std::vector<Segment> s;
  for (int i = 0; i < n; ++i) s.push_back({{Coord(7 * (i % 5)), Coord(20 * i)}, {Coord(300 + 11 * (i % 7)), Coord(20 * i)}});
  return s;
}
}  // namespace

TEST(Checker, SampledSearchTakesAboutOnePieceInNWhateverTheThreads) {
  const Diagram d = voronoi_of_polygons(linf::testing::block(3, linf::testing::Style::Octilinear, 6, 6)).diagram;
  const std::size_t n = d.pieces.size();
  ASSERT_GT(n, 2000u);
  const CheckReport one = check(d, kSampledSearchEvery, 1), two = check(d, kSampledSearchEvery, 2);
  EXPECT_TRUE(one.ok());
  EXPECT_EQ(one.searched_pieces, two.searched_pieces);
  EXPECT_GT(one.searched_pieces, n / (2 * kSampledSearchEvery));
  EXPECT_LT(one.searched_pieces, 2 * n / kSampledSearchEvery);
  EXPECT_EQ(one.sampled_points, check(d, 1, 1).sampled_points);  // every piece's owners still tested
  EXPECT_EQ(check(d, 1, 2).searched_pieces, n);
}

// A builder that lost sites (a halo or a far field too small) gives pieces that are right for
// their owners but run past a nearer site: only the closer-site search sees them.
TEST(Checker, SampledCheckRejectsADiagramBuiltWithoutSomeSites) {
  const std::vector<Segment> all = wires(200);
  std::vector<Segment> kept;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (i % 8 != 4) kept.push_back(all[i]);
  const Sites full = sites_of_plain({}, all);
  Diagram partial = voronoi_of_sites({}, kept).diagram;
  // The partial diagram's owners as indices among all the sites.
  std::map<std::tuple<Coord, Coord, Coord, Coord>, std::int32_t> index;
  for (std::size_t i = 0; i < full.sites.size(); ++i) {
    const Site& t = full.sites[i];
    index[{t.a.x, t.a.y, t.b.x, t.b.y}] = std::int32_t(i);
  }
  auto full_index = [&](std::int32_t s) {
    const Site& t = partial.sites.sites[std::size_t(s)];
    return index.at({t.a.x, t.a.y, t.b.x, t.b.y});
  };
  Diagram d;
  d.sites = full;
  d.clip = partial.clip;
  for (Piece p : partial.pieces) {
    p.a = full_index(p.a), p.b = full_index(p.b);
    d.pieces.push_back(p);
  }
  const CheckReport r = check(d, kSampledSearchEvery, 2);
  EXPECT_EQ(r.equidistance_errors + r.clearance_errors, 0u);
  EXPECT_GT(r.closer_site_errors, 0u);
  EXPECT_FALSE(r.ok());
}

// A fuzzer finding: a self-intersecting quadrilateral merged into a triangle at 10^8 DBU, one
// edge almost diagonal (312,569,806 across, 312,569,807 up). Near the vertex the segment's L1
// distance falls below its own end point's by about 1e-9 DBU, so the builder (exact) gives the
// segment the point's wedge. The checker took the two L1 values for a tie within rounding, gave
// it to the point by the rule and reported a missing piece; such a pair is now not clear.
TEST(Checker, ANearTieWithinRoundingIsNotDecided) {
  const std::vector<Polygon> layout = {
      {{{33406466, 275740160}, {33399298, 275740160}, {33399298, 275790336}, {33406466, 275790336}}, {}},
      {{{33686018, 308698624}, {33686018, 308698624}, {18238978, 293251584}, {18238978, 178047488},
        {33686018, 162600448}, {33686018, 162600448}}, {}},
      {{{-436068862, 470243840}, {-436068862, 470243840}, {-436068862, 2316800}, {33686018, 235800064},
        {33686018, 488960}, {33686018, 488960}}, {}}};
  DiagramOptions o;
  o.build.threads = 1;
  o.build.far_field_pass = false;
  const Result r = voronoi_of_polygons(layout, o);  // threw DiagramError ("no piece between")
  EXPECT_TRUE(r.check.ok());
  EXPECT_GT(r.check.pairs_separated, 0u);
}
