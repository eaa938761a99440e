// BoxTree: the packed R-tree of integer boxes (linf/box_tree.hpp), against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "linf/util/box_tree.hpp"

namespace {
using linf::BoxTree;
using linf::IntBox;

std::vector<IntBox> random_boxes(std::size_t n, unsigned seed, std::int32_t span, std::int32_t size) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int32_t> at(-span, span), wide(0, size);
  std::vector<IntBox> out;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t x = at(rng), y = at(rng);
    // Points, horizontal and vertical segments and boxes, as a layer's sites are.
    const int kind = int(i % 4);
    out.push_back({x, y, x + (kind & 1 ? wide(rng) : 0), y + (kind & 2 ? wide(rng) : 0)});
  }
  return out;
}

double distance2(const IntBox& b, double x, double y) {
  const double dx = x < b.x1 ? b.x1 - x : x > b.x2 ? x - b.x2 : 0.0;
  const double dy = y < b.y1 ? b.y1 - y : y > b.y2 ? y - b.y2 : 0.0;
  return dx * dx + dy * dy;
}

TEST(BoxTree, QueryFindsExactlyTheIntersectingBoxes) {
  for (const std::size_t n : {0u, 1u, 15u, 16u, 17u, 257u, 5000u}) {
    const std::vector<IntBox> boxes = random_boxes(n, unsigned(n) + 1, 1000, 60);
    const BoxTree tree(boxes.size(), [&](std::size_t i) { return boxes[i]; });
    EXPECT_EQ(tree.size(), n);
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::int32_t> at(-1100, 1100), wide(0, 200);
    for (int q = 0; q < 200; ++q) {
      const std::int32_t x = at(rng), y = at(rng);
      const IntBox box{x, y, x + wide(rng), y + wide(rng)};
      std::vector<std::int32_t> got, want;
      tree.query(box, [&](std::int32_t id) { got.push_back(id); });
      for (std::size_t i = 0; i < n; ++i)
        if (boxes[i].intersects(box)) want.push_back(std::int32_t(i));
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, want) << "n " << n << " query " << q;
    }
  }
}

TEST(BoxTree, TouchingBoxesIntersect) {
  const std::vector<IntBox> boxes{{0, 0, 10, 10}, {10, 10, 20, 20}, {11, 0, 20, 9}};
  const BoxTree tree(boxes.size(), [&](std::size_t i) { return boxes[i]; });
  std::vector<std::int32_t> got;
  tree.query({10, 10, 10, 10}, [&](std::int32_t id) { got.push_back(id); });
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<std::int32_t>{0, 1}));
}

TEST(BoxTree, NearestComesInOrderOfDistance) {
  const std::vector<IntBox> boxes = random_boxes(3000, 11, 5000, 300);
  const BoxTree tree(boxes.size(), [&](std::size_t i) { return boxes[i]; });
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> at(-6000, 6000);
  for (int q = 0; q < 100; ++q) {
    const double x = at(rng), y = at(rng);
    std::vector<double> got;
    std::vector<char> seen(boxes.size(), 0);
    tree.nearest(x, y, [&](std::int32_t id) {
      EXPECT_FALSE(seen[std::size_t(id)]) << "reported twice";
      seen[std::size_t(id)] = 1;
      got.push_back(distance2(boxes[std::size_t(id)], x, y));
      return got.size() < 25;
    });
    std::vector<double> want;
    for (const IntBox& b : boxes) want.push_back(distance2(b, x, y));
    std::sort(want.begin(), want.end());
    want.resize(25);
    ASSERT_EQ(got, want) << "query " << q;
  }
}

TEST(BoxTree, MillionsOfBoxesPastPagedsThreshold) {
  // 1.2 million boxes are 19 MB: past Paged's threshold, the tree is in its files.
  const std::vector<IntBox> boxes = random_boxes(1200000, 5, 1000000, 500);
  const BoxTree tree(boxes.size(), [&](std::size_t i) { return boxes[i]; });
  std::size_t found = 0, want = 0;
  const IntBox q{-20000, -20000, 20000, 20000};
  tree.query(q, [&](std::int32_t) { ++found; });
  for (const IntBox& b : boxes) want += b.intersects(q);
  EXPECT_GT(want, 0u);
  EXPECT_EQ(found, want);
}

}  // namespace
