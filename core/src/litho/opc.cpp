// The emulated OPC (opc.hpp): fragments, their moves read on the model's image tile by tile, the
// mask rebuilt from the moves.
#include "linf/litho/opc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "litho/clip.hpp"
#include "linf/litho/image.hpp"
#include "linf/litho/mask.hpp"
#include "util/parallel.hpp"

namespace linf::litho {

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("opc: " + what); }

// An edge's piece that moves as one, along the edge's outward normal (nx, ny), by `move` nm.
struct Fragment {
  std::int64_t a0 = 0;            // units along the edge from its first point: where it starts
  std::int64_t cx2 = 0, cy2 = 0;  // its middle on the drawn edge, half units
  int nx = 0, ny = 0;
};

// A ring cleaned of repeated and collinear points, with its edges' fragments: edge e (from
// pts[e] to pts[e + 1]) owns fragments [first[e], first[e + 1]).
struct Ring2 {
  std::vector<Point> pts;
  std::vector<std::size_t> first;
  bool hole = false;
};

struct Shape {
  std::vector<Ring2> rings;
  bool kept = false;  // an edge off the axes: left as drawn
  std::int64_t box[4] = {0, 0, 0, 0};
};

// The ring's points in units of 1 / kOpcScale DBU.
std::vector<Point> cleaned(const std::int64_t* p, std::size_t n) {
  std::vector<Point> r;
  for (std::size_t j = 0; j < n; ++j) {
    if (std::abs(p[2 * j]) > kCoordLimit / kOpcScale || std::abs(p[2 * j + 1]) > kCoordLimit / kOpcScale)
      fail("a layer coordinate beyond +-2^28 DBU (the corrected layer is held in quarter DBU)");
    const Point q{p[2 * j] * kOpcScale, p[2 * j + 1] * kOpcScale};
    if (r.empty() || r.back() != q) r.push_back(q);
  }
  while (r.size() > 1 && r.front() == r.back()) r.pop_back();
  // Collinear middles go (a merged layer has few): the corners of the rebuild assume that
  // consecutive edges turn.
  for (bool again = true; again && r.size() >= 3;) {
    again = false;
    for (std::size_t j = 0; j < r.size() && r.size() >= 3; ++j) {
      const Point& a = r[(j + r.size() - 1) % r.size()];
      const Point& b = r[j];
      const Point& c = r[(j + 1) % r.size()];
      const __int128 cross = __int128(b.x - a.x) * (c.y - b.y) - __int128(b.y - a.y) * (c.x - b.x);
      if (cross == 0) {
        r.erase(r.begin() + std::ptrdiff_t(j));
        again = true;
        break;
      }
    }
  }
  return r;
}

int sign(std::int64_t v) { return (v > 0) - (v < 0); }

}  // namespace

OpcResult correct_mask(const FlatPolygons& layer, double dbu_nm, const OpcModel& model, const OpcRules& rules,
                       int threads) {
  if (model.kernels == nullptr || model.kernels->count() == 0) fail("the model has no kernels");
  if (!(model.threshold > 0)) fail("the resist threshold must be positive");
  if (!(model.blur >= 0) || !std::isfinite(model.blur)) fail("the resist blur must be a number >= 0");
  if (!(dbu_nm > 0)) fail("the database unit must be positive");
  if (!(rules.width > 0) || !std::isfinite(rules.width)) fail("the typical width must be a positive number");
  if (rules.iterations < 0) fail("the number of iterations must not be negative");
  if (!(rules.feedback > 0 && rules.feedback <= 1)) fail("the feedback must lie in (0, 1]");
  const Kernels& kernels = *model.kernels;
  // Everything below is in units of 1 / kOpcScale DBU (the moves' grid), and the windows in
  // half units (clip_ring doubles).
  const double unit = dbu_nm / kOpcScale, P = kernels.period, half_unit = unit / 2;
  // The window in half units, a multiple of 4 inside the period; tiles of half of it.
  std::int64_t W = std::int64_t(std::floor(P / half_unit + 1e-9));
  W -= W % 4;
  if (W < 8) fail("the model's period is below one database unit");
  const std::int64_t T = W / 2;
  const double fragment = P / kernels.half(), step = rules.width / 10;
  const double inward = rules.width / 4, outward = rules.width / 2;

  // The shapes and their fragments.
  std::vector<Shape> shapes;
  std::vector<Fragment> frags;
  check_rings(layer, "opc");
  {
    std::size_t at = 0;
    for (std::size_t k = 0; k < layer.n_rings; ++k) {
      const std::int64_t c = layer.rings[k];
      const std::size_t n = std::size_t(c < 0 ? -c : c);
      if (c > 0) shapes.emplace_back();
      Ring2 r;
      r.pts = cleaned(layer.points + 2 * at, n);
      r.hole = c < 0;
      for (std::size_t j = 0; j < r.pts.size(); ++j) {
        const Point& a = r.pts[j];
        const Point& b = r.pts[(j + 1) % r.pts.size()];
        if (a.x != b.x && a.y != b.y) shapes.back().kept = true;
      }
      if (r.pts.size() < 4) shapes.back().kept = true;
      shapes.back().rings.push_back(std::move(r));
      at += n;
    }
    for (Shape& s : shapes) {
      s.box[0] = s.box[1] = std::numeric_limits<std::int64_t>::max();
      s.box[2] = s.box[3] = std::numeric_limits<std::int64_t>::min();
      for (const Ring2& r : s.rings)
        for (const Point& q : r.pts)
          s.box[0] = std::min(s.box[0], q.x), s.box[1] = std::min(s.box[1], q.y),
          s.box[2] = std::max(s.box[2], q.x), s.box[3] = std::max(s.box[3], q.y);
      if (s.kept) continue;
      for (Ring2& r : s.rings) {
        // The material lies left of an edge when an outer ring runs counter-clockwise or a hole
        // clockwise; the outward normal is then the edge's right.
        __int128 area = 0;
        for (std::size_t j = 0; j < r.pts.size(); ++j) {
          const Point& a = r.pts[j];
          const Point& b = r.pts[(j + 1) % r.pts.size()];
          area += __int128(a.x) * b.y - __int128(b.x) * a.y;
        }
        const int right = ((area > 0) != r.hole) ? 1 : -1;
        for (std::size_t e = 0; e < r.pts.size(); ++e) {
          r.first.push_back(frags.size());
          const Point& a = r.pts[e];
          const Point& b = r.pts[(e + 1) % r.pts.size()];
          const int ux = sign(b.x - a.x), uy = sign(b.y - a.y);
          const std::int64_t L = std::abs(b.x - a.x) + std::abs(b.y - a.y);
          const std::int64_t k = std::max<std::int64_t>(1, std::llround(double(L) * unit / fragment));
          for (std::int64_t j = 0; j < k; ++j) {
            Fragment f;
            f.a0 = std::int64_t(std::llround(double(L) * double(j) / double(k)));
            const std::int64_t a1 = std::int64_t(std::llround(double(L) * double(j + 1) / double(k)));
            f.cx2 = 2 * a.x + (f.a0 + a1) * ux, f.cy2 = 2 * a.y + (f.a0 + a1) * uy;
            f.nx = right * uy, f.ny = -right * ux;
            frags.push_back(f);
          }
        }
        r.first.push_back(frags.size());
      }
    }
  }
  OpcResult out;
  out.fragments = frags.size();
  out.scale = kOpcScale;
  for (const Shape& s : shapes) out.kept += s.kept;

  // A shape's rings with the moves (nm, rounded to the unit): for each edge a corner where the
  // previous edge's last fragment and this edge's first meet, then a jog wherever two of its
  // fragments moved differently.
  auto rebuild = [&](const Shape& s, const std::vector<double>& move, std::vector<std::int64_t>& pts,
                     std::vector<std::int64_t>& counts) {
    for (const Ring2& r : s.rings) {
      const std::size_t before = pts.size();
      const std::size_t m = r.pts.size();
      if (s.kept) {
        for (const Point& q : r.pts) pts.push_back(q.x), pts.push_back(q.y);
      } else {
        auto units = [&](std::size_t f) { return std::int64_t(std::llround(move[f] / unit)); };
        for (std::size_t e = 0; e < m; ++e) {
          const Point& a = r.pts[e];
          const Point& b = r.pts[(e + 1) % m];
          const std::int64_t ux = sign(b.x - a.x), uy = sign(b.y - a.y);
          const std::size_t last = r.first[(e + m - 1) % m + 1] - 1, f0 = r.first[e], f1 = r.first[e + 1];
          const std::int64_t dp = units(last), d0 = units(f0);
          pts.push_back(a.x + dp * frags[last].nx + d0 * frags[f0].nx);
          pts.push_back(a.y + dp * frags[last].ny + d0 * frags[f0].ny);
          for (std::size_t f = f0 + 1; f < f1; ++f) {
            const std::int64_t p = units(f - 1), q = units(f);
            if (p == q) continue;
            const Fragment& g = frags[f];
            pts.push_back(a.x + g.a0 * ux + p * g.nx), pts.push_back(a.y + g.a0 * uy + p * g.ny);
            pts.push_back(a.x + g.a0 * ux + q * g.nx), pts.push_back(a.y + g.a0 * uy + q * g.ny);
          }
        }
      }
      const std::int64_t n = std::int64_t((pts.size() - before) / 2);
      counts.push_back(r.hole ? -n : n);
    }
  };

  // Tiles: T x T half units from the layer's lower-left corner, each read in the window of side W
  // centred on it. A fragment is read in the tile that holds its middle; a shape is in every
  // window its box, grown by the largest outward move, meets.
  std::int64_t lo[2] = {std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::max()};
  std::int64_t hi[2] = {std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::min()};
  for (const Shape& s : shapes)
    if (!s.kept) lo[0] = std::min(lo[0], 2 * s.box[0]), lo[1] = std::min(lo[1], 2 * s.box[1]),
                 hi[0] = std::max(hi[0], 2 * s.box[2]), hi[1] = std::max(hi[1], 2 * s.box[3]);
  std::vector<std::vector<std::size_t>> tile_shapes, tile_frags;
  std::int64_t nx = 0, ny = 0;
  if (!frags.empty()) {
    nx = (hi[0] - lo[0]) / T + 1, ny = (hi[1] - lo[1]) / T + 1;
    tile_shapes.resize(std::size_t(nx * ny)), tile_frags.resize(std::size_t(nx * ny));
    auto floor_div = [](std::int64_t v, std::int64_t d) { return v >= 0 ? v / d : -((-v + d - 1) / d); };
    const std::int64_t grow = 2 * (std::int64_t(std::ceil(outward / unit)) + 1);
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const Shape& s = shapes[i];
      // Window (ix, iy) spans [lo + ix T - T / 2, lo + ix T + 3 T / 2] on x (W = 2 T).
      auto range = [&](std::int64_t b0, std::int64_t b1, std::int64_t l, std::int64_t count) {
        const std::int64_t first = std::max<std::int64_t>(0, floor_div(b0 - grow - l - 3 * T / 2, T));
        const std::int64_t last = std::min<std::int64_t>(count - 1, floor_div(b1 + grow - l + T / 2, T));
        return std::pair<std::int64_t, std::int64_t>{first, last};
      };
      const auto [x0, x1] = range(2 * s.box[0], 2 * s.box[2], lo[0], nx);
      const auto [y0, y1] = range(2 * s.box[1], 2 * s.box[3], lo[1], ny);
      for (std::int64_t ix = x0; ix <= x1; ++ix)
        for (std::int64_t iy = y0; iy <= y1; ++iy) tile_shapes[std::size_t(ix * ny + iy)].push_back(i);
    }
    for (std::size_t f = 0; f < frags.size(); ++f) {
      const std::int64_t ix = std::clamp<std::int64_t>((frags[f].cx2 - lo[0]) / T, 0, nx - 1);
      const std::int64_t iy = std::clamp<std::int64_t>((frags[f].cy2 - lo[1]) / T, 0, ny - 1);
      tile_frags[std::size_t(ix * ny + iy)].push_back(f);
    }
  }
  std::vector<std::size_t> busy;
  for (std::size_t k = 0; k < tile_frags.size(); ++k)
    if (!tile_frags[k].empty()) busy.push_back(k);

  const LineKernels lines(kernels);
  std::vector<double> move(frags.size(), 0.0), error(frags.size(), 0.0);
  // Every fragment's error on the current mask (Jacobi: all read before any moves, so the result
  // does not depend on the order of the tiles or the threads).
  auto read = [&]() {
    detail::parallel_for(busy.size(), threads, [&](unsigned, std::size_t b) {
      const std::size_t k = busy[b];
      const std::int64_t ix = std::int64_t(k) / ny, iy = std::int64_t(k) % ny;
      const std::int64_t ox = lo[0] + ix * T - T / 2, oy = lo[1] + iy * T - T / 2;
      std::vector<Polygon> polys;
      std::vector<std::int64_t> pts, counts;
      for (const std::size_t i : tile_shapes[k]) {
        pts.clear(), counts.clear();
        rebuild(shapes[i], move, pts, counts);
        Polygon q;
        std::size_t at = 0;
        for (std::size_t r = 0; r < counts.size(); ++r) {
          const std::size_t n = std::size_t(std::abs(counts[r]));
          Ring ring = clip_ring(pts.data() + 2 * at, n, ox, oy, ox + W, oy + W);
          at += n;
          if (ring.size() < 3) {
            if (r == 0) break;
            continue;
          }
          if (r == 0) q.outer = std::move(ring);
          else q.holes.push_back(std::move(ring));
        }
        if (!q.outer.empty()) polys.push_back(std::move(q));
      }
      const MaskSpectrum mask(polys, Window{{ox, oy}, half_unit}, P, kernels.half());
      // One line a row: fragments of vertical edges are read along x through their middle's y,
      // those of horizontal edges along y, and all in a tile on one line share its profile (the
      // two edges of a wire are cut alike, line ends sit on one track: testcase 3's fragments
      // take 0.55 lines each). A line runs through the window's centre, in +x or +y; a fragment
      // reads it at its middle, towards its outward normal.
      const std::vector<std::size_t>& mine = tile_frags[k];
      std::vector<std::pair<std::int64_t, std::size_t>> rows;  // (2 coordinate + axis, fragment)
      rows.reserve(mine.size());
      for (const std::size_t f : mine)
        rows.push_back({frags[f].nx != 0 ? 2 * (frags[f].cy2 - oy) : 2 * (frags[f].cx2 - ox) + 1, f});
      std::sort(rows.begin(), rows.end());
      const double centre = double(W / 2) * half_unit;
      std::vector<Probe> probes;
      for (std::size_t j = 0; j < rows.size(); ++j) {
        if (j > 0 && rows[j].first == rows[j - 1].first) continue;
        const double at = double(rows[j].first >> 1) * half_unit;
        probes.push_back((rows[j].first & 1) == 0 ? Probe{&mask, centre, at, 1.0, 0.0}
                                                  : Probe{&mask, at, centre, 0.0, 1.0});
      }
      std::vector<LineProfile> profiles = LineProfile::batch(lines, probes);
      std::size_t line = 0;
      for (std::size_t j = 0; j < rows.size(); ++j) {
        if (j > 0 && rows[j].first != rows[j - 1].first) ++line;
        LineProfile& profile = profiles[line];
        if (j == 0 || rows[j].first != rows[j - 1].first) profile.blur(model.blur);
        const Fragment& g = frags[rows[j].second];
        const bool along_x = g.nx != 0;
        const double t = double(along_x ? g.cx2 - ox : g.cy2 - oy) * half_unit - centre;
        const double n = along_x ? g.nx : g.ny;
        const double at = profile.at(t), slope = (profile.at(t + n) - profile.at(t - n)) / 2;
        // A nearly flat image says little of where its edge is: an error of at most the width.
        const double e = slope < 0 ? (at - model.threshold) / -slope : (at > model.threshold ? step : -step);
        error[rows[j].second] = std::clamp(e, -rules.width, rules.width);
      }
    });
    double sum = 0, most = 0;
    for (const double e : error) sum += e * e, most = std::max(most, std::abs(e));
    out.rms_epe.push_back(frags.empty() ? 0.0 : std::sqrt(sum / double(frags.size())));
    out.max_epe.push_back(most);
  };
  // A fragment whose error changes sign overshot: the mask moves its printed edge more than its
  // own move (the mask error enhancement of a low-k1 feature exceeds 1 / feedback), so its
  // feedback halves, and it settles instead of swinging.
  std::vector<double> gain(frags.size(), rules.feedback), last(frags.size(), 0.0);
  for (int it = 0; it <= rules.iterations; ++it) {
    read();
    if (it == rules.iterations) break;
    for (std::size_t f = 0; f < frags.size(); ++f) {
      if (it > 0 && (error[f] > 0) != (last[f] > 0) && error[f] != 0) gain[f] /= 2;
      last[f] = error[f];
      move[f] = std::clamp(move[f] - std::clamp(gain[f] * error[f], -step, step), -inward, outward);
    }
  }
  for (const Shape& s : shapes) rebuild(s, move, out.points, out.rings);
  return out;
}

}  // namespace linf::litho
