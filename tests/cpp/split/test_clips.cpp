// Clip libraries (linf/clips.hpp): the cells' names and labels as the plugin made them in
// Python ("%.4f", "%.4g"), and the clips asked for one at a time.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "linf/split/clips.hpp"

namespace {
using namespace linf;

TEST(Clips, NamesAsThePluginMadeThem) {
  // Python: "%s_r%06d_%s_%s" % (prefix, rank, type, ("%.4f" % score_um).replace(".", "p").replace("-", "m"))
  EXPECT_EQ(clip_name("CAL", {42, "sandwich", 0.03, 0.0245, 0.5, 1.0}), "CAL_r000042_sandwich_0p0245");
  // Decimal ties round as the doubles lie, as in Python: -0.00015 is just above -0.00015,
  // 0.00125 just above 0.00125.
  EXPECT_EQ(clip_name("VER", {1234567, "T", 0.05, -0.00015, 0, 0}), "VER_r1234567_T_m0p0001");
  EXPECT_EQ(clip_name("CAL", {7, "comb", 0, 0.00125, 0, 0}), "CAL_r000007_comb_0p0013");
  EXPECT_EQ(clip_name("CAL", {7, "comb", 0, 12.5, 0, 0}), "CAL_r000007_comb_12p5000");
}

TEST(Clips, LabelsAsThePluginMadeThem) {
  // Python: "#%d %s cd=%.4g score=%.4g norm=%.4g tiebreak=%.4g"
  EXPECT_EQ(clip_label({42, "internal", 0.045, 0.0452, 0.123456, 0.00001}),
            "#42 internal cd=0.045 score=0.0452 norm=0.1235 tiebreak=1e-05");
  EXPECT_EQ(clip_label({3, "external", 123456.0, 1.0, 1.0, 0.0}), "#3 external cd=1.235e+05 score=1 norm=1 tiebreak=0");
}

TEST(Clips, AskedForInOrderOnceEach) {
  // One 100 x 100 square; clip 0 holds it whole, clip 1 half of it and a marker, clip 2 nothing.
  const std::vector<std::int64_t> points{0, 0, 100, 0, 100, 100, 0, 100};
  const std::vector<std::int64_t> rings{4};
  const FlatPolygons layer{points.data(), 4, rings.data(), 1};
  std::vector<std::size_t> asked;
  const std::string path = ::testing::TempDir() + "clips_test.oas";
  const std::size_t shapes = write_clip_library(path, 0.001, layer, ClipLayers{}, 3, [&](std::size_t i, Clip& c) {
    asked.push_back(i);
    const std::int64_t x = i == 0 ? -10 : i == 1 ? 50 : 1000;
    c.name = clip_name("CAL", {std::int64_t(i + 1), "internal", 0.1, 0.1, 0.5, 0});
    c.label = clip_label({std::int64_t(i + 1), "internal", 0.1, 0.1, 0.5, 0});
    c.window = {x, -10, x + 120, 110};
    c.line = {x, 0, x, 100};
    c.at = {x, 50};
    c.markers.clear();
    if (i == 1) c.markers.push_back({60, 60, 70, 70});
  });
  EXPECT_EQ(asked, (std::vector<std::size_t>{0, 1, 2}));
  // Each clip: its cut shapes, the line, the label, the window; clip 1 also its marker.
  EXPECT_EQ(shapes, (1 + 3) + (1 + 3 + 1) + (0 + 3));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  char magic[13] = {};
  EXPECT_EQ(std::fread(magic, 1, 13, f), 13u);
  std::fclose(f);
  std::remove(path.c_str());
  EXPECT_EQ(std::string(magic, 13), "%SEMI-OASIS\r\n");
  EXPECT_THROW(write_clip_library(path, 0.001, layer, ClipLayers{}, 0, [](std::size_t, Clip&) {}), std::invalid_argument);
}

}  // namespace
