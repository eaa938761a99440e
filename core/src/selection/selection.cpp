#include "linf/selection/selection.hpp"

#include "linf/util/median.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

namespace linf {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;
using Entry = std::pair<BBox, std::int32_t>;

BBox to_bbox(const Box& b) { return BBox(BPoint(b.x1, b.y1), BPoint(b.x2, b.y2)); }

Box window_at(const Vec2& c, double side) {
  const double h = 0.5 * side;
  return {c.x - h, c.y - h, c.x + h, c.y + h};
}

// The loop shared by the fast and the brute-force selection: `query(window, out)` lists the
// markers the window covers.
template <class Query>
Selection run(const Spot* ranked, std::size_t n, std::size_t n_markers, double side, Query query) {
  Selection s;
  std::vector<char> done(n_markers, 0);
  std::vector<std::int32_t> hit;
  for (std::size_t i = 0; i < n && s.covered < std::int32_t(n_markers); ++i) {
    ++s.traversed;
    const Box w = window_at(ranked[i].at, side);
    hit.clear();
    query(w, hit);
    if (hit.empty()) {
      s.failed.push_back(std::int32_t(i));
      s.failed_by_type.add(ranked[i]);
      continue;
    }
    Window win;
    win.box = w;
    win.gauge = std::int32_t(i);
    for (std::int32_t m : hit)
      if (!done[m]) done[m] = 1, win.markers.push_back(m);
    if (win.markers.empty()) {
      ++s.redundant;
      continue;
    }
    std::sort(win.markers.begin(), win.markers.end());
    s.covered += std::int32_t(win.markers.size());
    s.used.push_back(std::int32_t(i));
    s.used_by_type.add(ranked[i]);
    s.windows.push_back(std::move(win));
  }
  return s;
}
}  // namespace

void Tally::add(const Spot& s) {
  const int t = std::clamp(s.type, 0, kTypes - 1);
  lo[t] = n[t] ? std::min(lo[t], s.norm) : s.norm;
  hi[t] = n[t] ? std::max(hi[t], s.norm) : s.norm;
  ++n[t];
}

bool covers(const Box& w, const Box& m, Cover mode) {
  switch (mode) {
    case Cover::Centre: {
      const double cx = 0.5 * (m.x1 + m.x2), cy = 0.5 * (m.y1 + m.y2);
      return cx > w.x1 && cx < w.x2 && cy > w.y1 && cy < w.y2;
    }
    case Cover::Inside: return m.x1 >= w.x1 && m.x2 <= w.x2 && m.y1 >= w.y1 && m.y2 <= w.y2;
    case Cover::Overlap: return m.x1 <= w.x2 && m.x2 >= w.x1 && m.y1 <= w.y2 && m.y2 >= w.y1;
  }
  return false;
}

Selection select_windows(const Spot* ranked, std::size_t n, const std::vector<Box>& markers, double side, Cover mode) {
  // Mode A queries the marker centres, B and C the marker boxes; each query is the closed
  // intersection with the window, then refined by the exact predicate (strictness, containment).
  std::vector<Entry> entries;
  entries.reserve(markers.size());
  for (std::size_t i = 0; i < markers.size(); ++i) {
    const Box& m = markers[i];
    if (mode == Cover::Centre) {
      const double cx = 0.5 * (m.x1 + m.x2), cy = 0.5 * (m.y1 + m.y2);
      entries.push_back({BBox(BPoint(cx, cy), BPoint(cx, cy)), std::int32_t(i)});
    } else {
      entries.push_back({to_bbox(m), std::int32_t(i)});
    }
  }
  const bgi::rtree<Entry, bgi::rstar<16>> tree(entries.begin(), entries.end());
  std::vector<Entry> found;
  return run(ranked, n, markers.size(), side, [&](const Box& w, std::vector<std::int32_t>& out) {
    found.clear();
    if (mode == Cover::Inside)
      tree.query(bgi::covered_by(to_bbox(w)), std::back_inserter(found));
    else
      tree.query(bgi::intersects(to_bbox(w)), std::back_inserter(found));
    for (const Entry& e : found)
      if (covers(w, markers[e.second], mode)) out.push_back(e.second);
  });
}

Selection select_windows_brute(const Spot* ranked, std::size_t n, const std::vector<Box>& markers, double side,
                               Cover mode) {
  return run(ranked, n, markers.size(), side, [&](const Box& w, std::vector<std::int32_t>& out) {
    for (std::size_t i = 0; i < markers.size(); ++i)
      if (covers(w, markers[i], mode)) out.push_back(std::int32_t(i));
  });
}

std::vector<std::int32_t> free_windows(const std::vector<Box>& taken, const Vec2* points, std::size_t n, double side) {
  // Windows by the grid cell (of the window side) of their lower-left corner: a window that
  // overlaps the square at b has its corner within one cell of b's.
  std::unordered_map<std::int64_t, std::vector<Box>> grid;
  auto cell = [&](double v) { return std::int64_t(std::floor(v / side)); };
  auto key = [](std::int64_t i, std::int64_t j) { return (i << 32) ^ (j & 0xffffffff); };
  auto overlap = [](const Box& a, const Box& b) { return a.x1 < b.x2 && b.x1 < a.x2 && a.y1 < b.y2 && b.y1 < a.y2; };
  auto add = [&](const Box& b) { grid[key(cell(b.x1), cell(b.y1))].push_back(b); };
  for (const Box& b : taken) add(b);
  std::vector<std::int32_t> kept;
  const double h = 0.5 * side;
  for (std::size_t k = 0; k < n; ++k) {
    const Box b{points[k].x - h, points[k].y - h, points[k].x + h, points[k].y + h};
    bool free = true;
    for (std::int64_t i = cell(b.x1) - 1; free && i <= cell(b.x2) + 1; ++i)
      for (std::int64_t j = cell(b.y1) - 1; free && j <= cell(b.y2) + 1; ++j) {
        const auto it = grid.find(key(i, j));
        if (it == grid.end()) continue;
        for (const Box& o : it->second)
          if (overlap(b, o)) { free = false; break; }
      }
    if (free) {
      add(b);
      kept.push_back(std::int32_t(k));
    }
  }
  return kept;
}

std::vector<Box> cover_points(std::vector<Vec2> points, double side) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
  });
  std::vector<char> gone(points.size(), 0);
  std::vector<Box> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (gone[i]) continue;
    const Box w{points[i].x - 1, points[i].y - 1, points[i].x - 1 + side, points[i].y - 1 + side};
    out.push_back(w);
    // Points are sorted by y, so those inside lie in a band starting here.
    for (std::size_t j = i; j < points.size() && points[j].y <= w.y2; ++j)
      if (!gone[j] && points[j].x >= w.x1 && points[j].x <= w.x2) gone[j] = 1;
  }
  return out;
}

double estimate_pitch_in_place(Paged<Weighted>& widths, Paged<Weighted>& spaces) {
  const double w = weighted_median_in_place(widths);
  spaces.resize(std::size_t(
      std::remove_if(spaces.begin(), spaces.end(), [&](const Weighted& p) { return p.value > 10 * w; }) - spaces.begin()));
  const double s = weighted_median_in_place(spaces);
  return w > 0 && s > 0 ? w + s : 0.0;
}

double estimate_pitch(const std::vector<std::pair<double, double>>& widths,
                      const std::vector<std::pair<double, double>>& spaces) {
  Paged<Weighted> w, s;
  for (const auto& [cd, extension] : widths) w.push_back({cd, extension});
  for (const auto& [cd, extension] : spaces) s.push_back({cd, extension});
  return estimate_pitch_in_place(w, s);
}

double estimate_pitch_of_gauges(const Strided<double>& cd, const Strided<double>& extension,
                                const Strided<std::int32_t>& types) {
  if (extension.size() != cd.size() || types.size() != cd.size())
    throw std::invalid_argument("one value a gauge in every column");
  Paged<Weighted> widths, spaces;
  for (std::size_t i = 0; i < cd.size(); ++i) {
    if (types[i] == 0) widths.push_back({cd[i], extension[i]});
    else if (types[i] == 1) spaces.push_back({cd[i], extension[i]});
  }
  return estimate_pitch_in_place(widths, spaces);
}

Cover cover_of(const std::string& mode) {
  if (mode == "A") return Cover::Centre;
  if (mode == "B") return Cover::Inside;
  if (mode == "C") return Cover::Overlap;
  throw std::invalid_argument("mode must be A, B or C");
}

}  // namespace linf
