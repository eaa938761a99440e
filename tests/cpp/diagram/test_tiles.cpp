// Tiles: the diagram built tile by tile is the diagram built in one piece, bit for bit, and a
// tile holds only the sites near it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/geometry/sites.hpp"
#include "layouts.hpp"

using namespace linf;
using linf::testing::block;

namespace {

using Key = std::tuple<int, int, double, double, double, double, double, double>;

std::vector<Key> keys(const std::vector<Piece>& v) {
  std::vector<Key> k;
  for (const Piece& p : v) k.emplace_back(p.a, p.b, p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2);
  std::sort(k.begin(), k.end());
  return k;
}

}  // namespace

TEST(Tiles, SamePiecesForEveryTileSize) {
  const linf::testing::Style styles[] = {linf::testing::Style::Rectilinear, linf::testing::Style::Octilinear,
                                         linf::testing::Style::AnyAngle};
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const Sites s = sites_of_polygons(merge_polygons(block(seed, styles[seed % 3], 12, 10)));
    const Box clip = clip_box(s);
    BuildOptions whole;
    whole.threads = 2;
    BuildStats st_whole;
    const std::vector<Key> ref = keys(build_pieces(s, clip, whole, &st_whole));
    EXPECT_EQ(st_whole.tiles, 1u);
    ASSERT_GE(st_whole.tasks, 64u) << "the block should need several task levels";
    const double side = std::max(clip.x2 - clip.x1, clip.y2 - clip.y1) / 3;  // the sites' box, about
    for (double frac : {0.5, 0.2, 0.01}) {
      BuildOptions tiled = whole;
      tiled.tile_size = frac * side;
      tiled.threads = frac < 0.2 ? 1 : 2;
      BuildStats st;
      const std::vector<Key> got = keys(build_pieces(s, clip, tiled, &st));
      EXPECT_GT(st.tiles, 1u) << "tile " << tiled.tile_size;
      EXPECT_EQ(st.tasks, st_whole.tasks);
      // A tile holds its own sites and its halo, not the layer.
      if (frac < 0.2) EXPECT_LT(st.largest_tile_sites, s.sites.size() / 2) << "tile " << tiled.tile_size;
      ASSERT_EQ(got.size(), ref.size()) << "seed " << seed << " tile " << tiled.tile_size;
      for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], ref[i]) << "seed " << seed << " piece " << i;
    }
  }
}

// Disks drawn with many vertices take the builder's other path (a crowded box solved whole,
// subdivision.hpp curved()); its decisions, too, must not depend on the tile.
TEST(Tiles, CurvedShapesTheSameForEveryTileSize) {
  std::vector<Polygon> p;
  for (int i = 0; i < 9; ++i) {
    Ring r;
    const int n = 300 + 37 * i;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / n + 0.1 * i;
      r.push_back({Coord(50000 * (i % 3) + std::llround(20000 * std::cos(a))),
                   Coord(50000 * (i / 3) + std::llround((12000 + 1000 * i) * std::sin(a)))});
    }
    p.push_back({r, {}});
  }
  const Sites s = sites_of_polygons(merge_polygons(p));
  const Box clip = clip_box(s);
  BuildOptions whole, plain;
  whole.threads = 2;
  plain.threads = 2;
  plain.crowded_sites = 0;  // never solve a crowded box whole
  BuildStats st_whole, st_plain;
  const std::vector<Key> ref = keys(build_pieces(s, clip, whole, &st_whole));
  build_pieces(s, clip, plain, &st_plain);
  ASSERT_LT(st_whole.solves, st_plain.solves) << "the crowded path should be taken";
  const double side = std::max(clip.x2 - clip.x1, clip.y2 - clip.y1) / 3;
  for (double frac : {0.5, 0.1}) {
    BuildOptions tiled = whole;
    tiled.tile_size = frac * side;
    BuildStats st;
    const std::vector<Key> got = keys(build_pieces(s, clip, tiled, &st));
    EXPECT_GT(st.tiles, 1u) << "tile " << tiled.tile_size;
    ASSERT_EQ(got.size(), ref.size()) << "tile " << tiled.tile_size;
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], ref[i]) << "tile " << tiled.tile_size << " piece " << i;
  }
}

TEST(Tiles, TiledDiagramPassesTheChecker) {
  DiagramOptions o;
  o.build.tile_size = 500;
  o.checker.crossing_pairs = 4000;
  const Result r = voronoi_of_polygons(block(7, linf::testing::Style::Octilinear, 8, 8), o);
  EXPECT_TRUE(r.check.ok());
  EXPECT_GT(r.diagram.pieces.size(), 1000u);
}

TEST(Tiles, IsolatedShapesFarApart) {
  // Tasks far from every site must still find their owners (the halo grows until it does).
  std::vector<Polygon> p{linf::testing::box(0, 0, 10, 10), linf::testing::box(100000, 0, 100010, 10),
                         linf::testing::box(0, 90000, 10, 90010)};
  for (Polygon q : linf::testing::random_layout(5, linf::testing::Style::Rectilinear, 40, 2000)) {
    for (Point& v : q.outer) v.x += 50000, v.y += 50000;
    for (Ring& h : q.holes)
      for (Point& v : h) v.x += 50000, v.y += 50000;
    p.push_back(q);
  }
  const Sites s = sites_of_polygons(merge_polygons(p));
  BuildOptions whole, tiled;
  tiled.tile_size = 3000;
  const Box clip = clip_box(s);
  EXPECT_EQ(keys(build_pieces(s, clip, whole)), keys(build_pieces(s, clip, tiled)));
  DiagramOptions o;
  o.build = tiled;
  EXPECT_TRUE(voronoi_of_polygons(p, o).check.ok());
}

// Automatic tiles are chosen by the fullest tile, not by the layer's average: a dense array in
// one quadrant of an otherwise empty box (39,224 sites; 2^16 a tile on average made one tile
// of the whole layer) is cut until no tile holds more than 2^15 sites of its own. A tile's
// working memory grows with its sites.
TEST(Tiles, AutomaticTilesBoundTheFullestTile) {
  std::vector<Polygon> p;
  for (int j = 0; j < 70; ++j)
    for (int i = 0; i < 70; ++i) p.push_back(linf::testing::box(100 * i, 100 * j, 100 * i + 50, 100 * j + 50));
  for (auto [x, y] : {std::pair{13950, 0}, std::pair{0, 13950}, std::pair{13950, 13950}})
    p.push_back(linf::testing::box(x, y, x + 50, y + 50));
  const Sites s = sites_of_polygons(merge_polygons(p));
  const Box clip = clip_box(s);
  BuildOptions whole;
  whole.threads = 2;
  const std::vector<Key> ref = keys(build_pieces(s, clip, whole));
  BuildOptions automatic = whole;
  automatic.tile_size = -1;
  BuildStats st;
  const std::vector<Key> got = keys(build_pieces(s, clip, automatic, &st));
  // 2 x 2 tiles leave the array whole in one; 4 x 4 cut it in four. A tile's halo reaches into
  // the array from the empty field around it, so the fullest holds about half the sites.
  EXPECT_EQ(st.tiles, 16u);
  EXPECT_LT(st.largest_tile_sites, 6 * s.sites.size() / 10) << st.tiles << " tiles";
  ASSERT_EQ(got.size(), ref.size());
  EXPECT_TRUE(got == ref);
}
