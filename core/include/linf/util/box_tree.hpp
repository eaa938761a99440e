// BoxTree: a static R-tree of integer boxes, packed once, for the whole-layer indexes (the
// checker's sites, the polygons grouped for merging and cut into clips).
//
// Why not Boost's rtree: on a layer of millions of sites its nodes are anonymous memory the
// process must hold to the end, and its packing first copies every entry into a temporary
// vector as large again. Here the boxes are sorted along a Hilbert curve of their centres and
// grouped 16 to a node, level by level, in Paged arrays: past Paged's threshold they are pages
// of a temporary file that the kernel may write out and drop (see paged.hpp). 20 bytes a box
// and a sixteenth more for the levels above.
//
// Boxes are closed: touching boxes intersect. Ids are 0 .. n-1 as given to the constructor.
#pragma once
#include <algorithm>
#include <cstdint>
#include <queue>
#include <vector>

#include "linf/util/paged.hpp"

namespace linf {

struct IntBox {
  std::int32_t x1, y1, x2, y2;
  bool intersects(const IntBox& o) const { return x1 <= o.x2 && o.x1 <= x2 && y1 <= o.y2 && o.y1 <= y2; }
};

class BoxTree {
 public:
  BoxTree() = default;
  // box_of(i) -> IntBox for i in [0, n), each called twice.
  template <class BoxOf>
  BoxTree(std::size_t n, BoxOf&& box_of) {
    if (n == 0) return;
    std::int64_t lo_x = INT32_MAX, lo_y = INT32_MAX, hi_x = INT32_MIN, hi_y = INT32_MIN;
    for (std::size_t i = 0; i < n; ++i) {
      const IntBox b = box_of(i);
      lo_x = std::min<std::int64_t>(lo_x, b.x1), lo_y = std::min<std::int64_t>(lo_y, b.y1);
      hi_x = std::max<std::int64_t>(hi_x, b.x2), hi_y = std::max<std::int64_t>(hi_y, b.y2);
    }
    // Hilbert index of the centre on a 2^16 grid over the whole box; the id in the low half,
    // so one sort of 64-bit keys orders the leaves (ties by id: the tree is reproducible).
    Paged<std::uint64_t> keys;
    keys.reserve(n);
    const double sx = 65535.0 / double(std::max<std::int64_t>(1, hi_x - lo_x));
    const double sy = 65535.0 / double(std::max<std::int64_t>(1, hi_y - lo_y));
    for (std::size_t i = 0; i < n; ++i) {
      const IntBox b = box_of(i);
      const double cx = 0.5 * (double(b.x1) + double(b.x2)) - double(lo_x), cy = 0.5 * (double(b.y1) + double(b.y2)) - double(lo_y);
      const std::uint32_t h = hilbert(std::uint32_t(cx * sx), std::uint32_t(cy * sy));
      keys.push_back(std::uint64_t(h) << 32 | std::uint64_t(i));
    }
    std::sort(keys.begin(), keys.end());
    ids_.resize(n);
    for (std::size_t k = 0; k < n; ++k) ids_[k] = std::int32_t(keys[k] & 0xffffffffu);
    keys = Paged<std::uint64_t>();
    boxes_.reserve(n + n / (kNode - 1) + 2);
    for (std::size_t k = 0; k < n; ++k) boxes_.push_back(box_of(std::size_t(ids_[k])));
    level_.push_back(0);
    for (std::size_t begin = 0, end = n; end - begin > 1;) {
      for (std::size_t c = begin; c < end; c += kNode) {
        IntBox u = boxes_[c];
        for (std::size_t j = c + 1; j < std::min(end, c + kNode); ++j) {
          const IntBox& b = boxes_[j];
          u = {std::min(u.x1, b.x1), std::min(u.y1, b.y1), std::max(u.x2, b.x2), std::max(u.y2, b.y2)};
        }
        boxes_.push_back(u);
      }
      begin = end, end = boxes_.size();
      level_.push_back(begin);
    }
  }

  std::size_t size() const { return ids_.size(); }

  // f(id) for every box that intersects q, in the order of the leaves.
  template <class F>
  void query(const IntBox& q, F&& f) const {
    if (ids_.empty()) return;
    const int root_level = int(level_.size()) - 1;
    if (!boxes_[level_[std::size_t(root_level)]].intersects(q)) return;
    if (root_level == 0) {
      f(ids_[0]);
      return;
    }
    // Only nodes that meet q go on the stack: a node's children are tested where it is taken
    // off, most of them missing (the checker's queries are a few DBU, the nodes 16 boxes).
    Node stack[16 * kNode];  // kNode - 1 siblings left at most per level, and at most 9 levels
    int top = 0;
    stack[top++] = pack(root_level, 0);
    while (top > 0) {
      const Node e = stack[--top];
      const int lv = int(e >> 40);
      const std::size_t at = std::size_t(e & kIndexMask);
      const std::size_t first = at * kNode, last = std::min(first + kNode, level_size(lv - 1));
      const IntBox* child = &boxes_[level_[std::size_t(lv - 1)]];
      if (lv == 1) {
        for (std::size_t c = first; c < last; ++c)
          if (child[c].intersects(q)) f(ids_[c]);
        continue;
      }
      for (std::size_t c = last; c-- > first;)
        if (child[c].intersects(q)) stack[top++] = pack(lv - 1, c);
    }
  }

  // Boxes by increasing Euclidean distance from (x, y) (0 inside), f(id) for each until it
  // returns false.
  template <class F>
  void nearest(double x, double y, F&& f) const {
    if (ids_.empty()) return;
    using Item = std::pair<double, Node>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    const int root_level = int(level_.size()) - 1;
    open.push({0.0, pack(root_level, 0)});
    while (!open.empty()) {
      const Node e = open.top().second;
      open.pop();
      const int lv = int(e >> 40);
      const std::size_t at = std::size_t(e & kIndexMask);
      if (lv == 0) {
        if (!f(ids_[at])) return;
        continue;
      }
      const std::size_t first = at * kNode, last = std::min(first + kNode, level_size(lv - 1));
      for (std::size_t c = first; c < last; ++c) open.push({distance2(boxes_[level_[std::size_t(lv - 1)] + c], x, y), pack(lv - 1, c)});
    }
  }

 private:
  static constexpr std::size_t kNode = 16;
  // A node as one integer: its level above bit 40, its index in its level below.
  using Node = std::uint64_t;
  static constexpr Node kIndexMask = (Node(1) << 40) - 1;

  static Node pack(int level, std::size_t index) { return Node(level) << 40 | Node(index); }

  std::size_t level_size(int lv) const {
    return (std::size_t(lv) + 1 < level_.size() ? level_[std::size_t(lv) + 1] : boxes_.size()) - level_[std::size_t(lv)];
  }

  static double distance2(const IntBox& b, double x, double y) {
    const double dx = x < b.x1 ? b.x1 - x : x > b.x2 ? x - b.x2 : 0.0;
    const double dy = y < b.y1 ? b.y1 - y : y > b.y2 ? y - b.y2 : 0.0;
    return dx * dx + dy * dy;
  }

  // The position of (x, y) along a Hilbert curve over [0, 2^16)^2.
  static std::uint32_t hilbert(std::uint32_t x, std::uint32_t y) {
    std::uint32_t d = 0;
    for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
      const std::uint32_t rx = (x & s) > 0, ry = (y & s) > 0;
      d += s * s * ((3 * rx) ^ ry);
      if (ry == 0) {
        if (rx == 1) x = 65535 - x, y = 65535 - y;
        std::swap(x, y);
      }
    }
    return d;
  }

  Paged<IntBox> boxes_;          // level 0 (the boxes, in Hilbert order), then each level up
  Paged<std::int32_t> ids_;      // level 0's position -> id
  std::vector<std::size_t> level_;  // where each level begins in boxes_; the last holds the root
};

}  // namespace linf
