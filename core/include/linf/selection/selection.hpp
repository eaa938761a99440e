// Pattern selection (thesis 5.2): windows around ranked gauges that cover the markers.
//
//   in:  gauge points in rank order, marker boxes (a point marker is a box of zero size), the
//        window side, the coverage mode;
//   out: the kept windows (one per useful gauge) with the markers each newly covers, and the
//        used / failed / redundant gauges, as the thesis's Tables 5.2-5.4 count them.
//
// The traversal goes down the ranked gauges and stops once every marker is covered. A gauge is
//   used      (G_u) if its window covers a marker not covered before: the window is kept;
//   failed    (G_f) if its window covers no marker at all;
//   redundant      if its window covers only markers already covered: discarded, not failed.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "linf/util/median.hpp"
#include "linf/util/paged.hpp"
#include "linf/util/strided.hpp"
#include "linf/geometry/piece.hpp"

namespace linf {

// How a window covers a marker: (A) the marker's centre strictly inside the window,
// (B) the whole marker inside the window (closed), (C) marker and window meet (closed sets).
enum class Cover : std::uint8_t { Centre, Inside, Overlap };

// The mode by its letter, "A", "B" or "C"; throws std::invalid_argument for any other.
Cover cover_of(const std::string& mode);

struct Spot {  // a gauge as the selection sees it
  Vec2 at;
  std::int32_t id = -1;   // caller's gauge id
  std::int32_t type = 0;  // caller's type index, 0..kTypes-1, for the tallies
  double norm = 0;        // normalised score, for the tallies
};

constexpr int kTypes = 5;

// Count and normalised-score range of gauges per type (Tables 5.5, 5.6).
struct Tally {
  std::array<std::int32_t, kTypes> n{};
  std::array<double, kTypes> lo{}, hi{};
  void add(const Spot& s);
};

struct Window {
  Box box;
  std::int32_t gauge = -1;            // index into the ranked spots
  std::vector<std::int32_t> markers;  // markers this window covers first (marker indices)
};

struct Selection {
  std::vector<Window> windows;       // kept, in gauge order
  std::vector<std::int32_t> used;    // spot indices (G_u), one per window
  std::vector<std::int32_t> failed;  // spot indices (G_f)
  std::int32_t redundant = 0;
  std::int32_t traversed = 0;        // gauges looked at before every marker was covered
  std::int32_t covered = 0;          // M_c
  Tally used_by_type, failed_by_type;
};

// Spatial queries go through a Boost.Geometry R-tree over the markers. The n ranked spots may
// be any contiguous array (a full layer's are a Paged one: tens of millions).
Selection select_windows(const Spot* ranked, std::size_t n, const std::vector<Box>& markers, double side, Cover mode);

// The same by brute force over all markers: the test oracle for select_windows.
Selection select_windows_brute(const Spot* ranked, std::size_t n, const std::vector<Box>& markers, double side,
                               Cover mode);

inline Selection select_windows(const std::vector<Spot>& ranked, const std::vector<Box>& markers, double side,
                                Cover mode) {
  return select_windows(ranked.data(), ranked.size(), markers, side, mode);
}
inline Selection select_windows_brute(const std::vector<Spot>& ranked, const std::vector<Box>& markers, double side,
                                      Cover mode) {
  return select_windows_brute(ranked.data(), ranked.size(), markers, side, mode);
}

bool covers(const Box& window, const Box& marker, Cover mode);

// The thesis's window-reduction heuristic: repeatedly take the bottommost remaining point
// (least y, then least x) at (bx, by), put a window of the given side with its lower-left corner
// at (bx - 1, by - 1), drop every point inside it (closed). Returns the windows in order.
std::vector<Box> cover_points(std::vector<Vec2> points, double side);

// The split's extra patterns (thesis 5.4: calibration needs material beyond the windows that
// cover markers): in order, each point whose window (the square of the given side centred on
// it) overlaps no window before it, `taken` first and then those kept here. Overlap is of open
// boxes: windows that only touch do not overlap. `taken` windows are no wider than `side`.
// Returns the indices of the kept points.
std::vector<std::int32_t> free_windows(const std::vector<Box>& taken, const Vec2* points, std::size_t n, double side);

// The layer's pitch when none is given: the typical width plus the typical space, each the
// median of gauge CDs weighted by their extension; spaces wider than ten typical widths are
// the far field around the layout's outer shapes, not pattern, and are left out. Pairs are
// (cd, extension). Returns 0 without widths or spaces.
double estimate_pitch(const std::vector<std::pair<double, double>>& widths,
                      const std::vector<std::pair<double, double>>& spaces);

// The same, reordering and shortening `widths` and `spaces` in place: a full layer's pairs are
// hundreds of MB, and copies of them were most of the flow's memory while it took the pitch.
double estimate_pitch_in_place(Paged<Weighted>& widths, Paged<Weighted>& spaces);

// The same from the gauge table's columns, one value a gauge in each: cd, extension and type
// index (0 internal: the widths; 1 external: the spaces; others left out). Throws
// std::invalid_argument if the columns differ in length.
double estimate_pitch_of_gauges(const Strided<double>& cd, const Strided<double>& extension,
                                const Strided<std::int32_t>& types);

}  // namespace linf
