// Pattern classes: windows whose clips are alike are one pattern (the ICCAD 2016 contest's
// pattern classification), so that thousands of marker windows become the patterns they are.
//
//   in:  the layer's polygons (flat, as drawn), the windows (DBU boxes, in the caller's order:
//        the selection's, most critical gauge first), the rule;
//   out: for each window its pattern; for each pattern its representative window and count.
//
// A window's clip is the layer's merged shapes inside it, seen from the window's centre. Two
// clips match when, under one of the 8 symmetries of the square (rotations by 90 degrees and
// mirrors) about their centres, their XOR is small:
//   Area: its area is at most `area_fraction` of the window's area;
//   Edge: it holds nothing wider than `edge` DBU (it vanishes when shrunk by edge / 2: every
//         edge moved by at most `edge`, slivers and specks of that width only).
// Windows of different sizes never match. Leader clustering: each window in turn joins the
// first pattern (in order of creation) whose representative it matches, or starts a new one
// with itself as the representative; so the representative is the pattern's first window in
// the caller's order, and the result depends on that order only.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"

namespace linf {

struct ClassRule {
  enum By : std::uint8_t { Area, Edge } by = Area;
  double area_fraction = 0.05;  // Area: XOR area over the window's area
  std::int64_t edge = 2;        // Edge: DBU
};

struct PatternClasses {
  std::vector<std::int32_t> of_window;       // the pattern of each window
  std::vector<std::int32_t> representative;  // the first window of each pattern
  std::vector<std::int32_t> count;           // windows in each pattern
  std::size_t compared = 0;                  // exact XOR comparisons made (after the filter)
};

// threads: the clips are made on this many (0: one per core); the classes do not depend on it.
PatternClasses classify_patterns(const FlatPolygons& layer, const std::vector<std::array<std::int64_t, 4>>& windows,
                                 const ClassRule& rule, int threads = 0);

}  // namespace linf
