// Printability of gauges (printability.hpp): one window a context, clipped from the layer,
// imaged with the model and read along the measurement line with the threshold resist.
#include "linf/litho/printability.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "litho/clip.hpp"
#include "linf/litho/chunks.hpp"
#include "linf/litho/image.hpp"
#include "linf/litho/mask.hpp"
#include "linf/litho/resist.hpp"
#include "util/parallel.hpp"

namespace linf::litho {

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("printability: " + what); }

// The layer's polygons and a grid of buckets of side `cell` (the window's side): a window meets
// at most 2 x 2 buckets, so finding its shapes costs a few lookups. Kept here rather than the
// core's PolygonIndex / BoxTree so that linf_litho stays apart from the diagram's library.
class Layer {
 public:
  Layer(const FlatPolygons& in, std::int64_t cell) : in_(in), cell_(cell) {
    check_rings(in, "printability");
    std::size_t at = 0;
    for (std::size_t k = 0; k < in.n_rings; ++k) {
      const std::int64_t c = in.rings[k];
      const std::size_t n = std::size_t(c < 0 ? -c : c);
      if (c > 0) polys_.push_back({k, 0, at, {}});
      Poly& p = polys_.back();
      ++p.rings;
      if (c > 0) {
        std::int64_t b[4] = {INT64_MAX, INT64_MAX, INT64_MIN, INT64_MIN};
        for (std::size_t j = at; j < at + n; ++j) {
          const std::int64_t x = in.points[2 * j], y = in.points[2 * j + 1];
          if (std::abs(x) > kCoordLimit || std::abs(y) > kCoordLimit) fail("a layer coordinate beyond +-2^30 DBU");
          b[0] = std::min(b[0], x), b[1] = std::min(b[1], y), b[2] = std::max(b[2], x), b[3] = std::max(b[3], y);
        }
        std::copy(b, b + 4, p.box);
      }
      at += n;
    }
    for (std::size_t i = 0; i < polys_.size(); ++i) {
      const Poly& p = polys_[i];
      for (std::int64_t gx = floor_div(p.box[0]); gx <= floor_div(p.box[2]); ++gx)
        for (std::int64_t gy = floor_div(p.box[1]); gy <= floor_div(p.box[3]); ++gy) buckets_[key(gx, gy)].push_back(i);
    }
  }

  // The shapes meeting the box [x0, x0 + w] x [y0, y0 + w] given in half DBU (doubled
  // coordinates, so that a window centred on a gauge point at a half DBU is exactly centred),
  // clipped to it, in half DBU.
  std::vector<Polygon> clip(std::int64_t x0, std::int64_t y0, std::int64_t w) const {
    std::vector<Polygon> out;
    for (std::size_t i : meeting(x0, y0, w)) {
      const Poly& p = polys_[i];
      Polygon q;
      std::size_t at = p.first_point;
      for (std::size_t r = 0; r < p.rings; ++r) {
        const std::int64_t c = in_.rings[p.first_ring + r];
        const std::size_t n = std::size_t(c < 0 ? -c : c);
        Ring ring = clip_ring(in_.points + 2 * at, n, x0, y0, x0 + w, y0 + w);
        at += n;
        if (ring.size() < 3) {
          if (r == 0) break;  // the outer ring leaves nothing: nor do its holes
          continue;
        }
        if (r == 0) q.outer = std::move(ring);
        else q.holes.push_back(std::move(ring));
      }
      if (!q.outer.empty()) out.push_back(std::move(q));
    }
    return out;
  }

  // The polygons (their numbers, ascending) whose boxes meet that box: those clip() clips.
  std::vector<std::size_t> meeting(std::int64_t x0, std::int64_t y0, std::int64_t w) const {
    std::vector<std::size_t> ids;
    const std::int64_t lx = floor_half(x0), ly = floor_half(y0), hx = floor_half(x0 + w) + 1, hy = floor_half(y0 + w) + 1;
    for (std::int64_t gx = floor_div(lx); gx <= floor_div(hx); ++gx)
      for (std::int64_t gy = floor_div(ly); gy <= floor_div(hy); ++gy) {
        const auto it = buckets_.find(key(gx, gy));
        if (it != buckets_.end()) ids.insert(ids.end(), it->second.begin(), it->second.end());
      }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    ids.erase(std::remove_if(ids.begin(), ids.end(), [&](std::size_t i) {
      const Poly& p = polys_[i];
      return 2 * p.box[0] > x0 + w || 2 * p.box[2] < x0 || 2 * p.box[1] > y0 + w || 2 * p.box[3] < y0;
    }), ids.end());
    return ids;
  }

  // Polygon i's rings and points, appended to flat arrays as FlatPolygons views them.
  void append(std::size_t i, std::vector<std::int64_t>& points, std::vector<std::int64_t>& rings) const {
    const Poly& p = polys_[i];
    std::size_t at = p.first_point;
    for (std::size_t r = 0; r < p.rings; ++r) {
      const std::int64_t c = in_.rings[p.first_ring + r];
      const std::size_t n = std::size_t(c < 0 ? -c : c);
      rings.push_back(c);
      points.insert(points.end(), in_.points + 2 * at, in_.points + 2 * (at + n));
      at += n;
    }
  }

 private:
  struct Poly {
    std::size_t first_ring, rings, first_point;
    std::int64_t box[4];
  };

  static std::int64_t floor_half(std::int64_t v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }
  std::int64_t floor_div(std::int64_t v) const { return v >= 0 ? v / cell_ : -((-v + cell_ - 1) / cell_); }
  static std::uint64_t key(std::int64_t gx, std::int64_t gy) {
    return (std::uint64_t(std::uint32_t(std::int32_t(gx))) << 32) | std::uint32_t(std::int32_t(gy));
  }

  FlatPolygons in_;
  std::int64_t cell_;
  std::vector<Poly> polys_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> buckets_;
};

// The window in half DBU, an even number of them inside the period (the mask refuses points
// beyond it), centred exactly on the gauge point (a gauge point lies on the half-DBU grid).
std::int64_t window_side(double period, double dbu_nm) {
  if (!(dbu_nm > 0)) fail("the database unit must be positive");
  std::int64_t W = std::int64_t(std::floor(period / (dbu_nm / 2) + 1e-9));
  W -= W % 2;
  if (W < 4) fail("the model's period is below two database units");
  return W;
}

std::int64_t window_origin(double c, std::int64_t W) { return std::int64_t(std::llround(2 * c)) - W / 2; }

}  // namespace

std::vector<LayerPart> window_shapes(const FlatPolygons& layer, double dbu_nm, double period, const Strided<double>& cx,
                                     const Strided<double>& cy, const std::vector<std::size_t>& starts) {
  if (cx.size() != cy.size()) fail("the gauge points' x and y have different lengths");
  for (std::size_t k = 0; k < starts.size(); ++k)
    if (starts[k] > cx.size() || (k > 0 && starts[k] < starts[k - 1])) fail("the chunks' starts must ascend within the points");
  const std::int64_t W = window_side(period, dbu_nm);
  const Layer shapes(layer, std::max<std::int64_t>(W / 2, 1));
  std::vector<LayerPart> parts;
  std::vector<std::size_t> ids;  // a chunk's polygons: its own, never a pass over the layer's
  for (std::size_t c = 0; c + 1 < starts.size(); ++c) {
    ids.clear();
    for (std::size_t k = starts[c]; k < starts[c + 1]; ++k)
      for (std::size_t i : shapes.meeting(window_origin(cx[k], W), window_origin(cy[k], W), W)) ids.push_back(i);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    LayerPart& part = parts.emplace_back();
    for (std::size_t i : ids) shapes.append(i, part.points, part.rings);
  }
  return parts;
}

Printability printability(const FlatPolygons& layer, double dbu_nm, const GaugeColumns& g, const PrintModel& model,
                          int threads) {
  if (model.kernels == nullptr || model.kernels->count() == 0) fail("the model has no kernels");
  const Kernels& kernels = *model.kernels;
  if (!(model.threshold > 0)) fail("the resist threshold must be positive");
  if (!(dbu_nm > 0)) fail("the database unit must be positive");
  if (!(model.dose >= 0 && model.dose < 1)) fail("the dose latitude must lie in [0, 1)");
  if (!(model.blur >= 0) || !std::isfinite(model.blur)) fail("the resist blur must be a number >= 0");
  if (model.defocus && (model.defocus->count() == 0 || model.defocus->size != kernels.size ||
                        model.defocus->period != kernels.period))
    fail("the defocus kernels must have the focus kernels' period and size");
  const std::size_t n = g.size();
  for (const std::size_t m : {g.cy.size(), g.x1.size(), g.y1.size(), g.x2.size(), g.y2.size(), g.type.size(), g.cd.size()})
    if (m != n) fail("the gauge columns have different lengths");
  if (g.context.size() != 0 && g.context.size() != n) fail("the context ids are not one a gauge");
  const double P = kernels.period;
  const double half_dbu = dbu_nm / 2;
  const std::int64_t W = window_side(P, dbu_nm);
  auto origin = [&](double c) { return window_origin(c, W); };
  for (std::size_t i = 0; i < n; ++i) {
    const double cx = g.cx[i], cy = g.cy[i];
    const std::int64_t ox = origin(cx), oy = origin(cy);
    auto inside = [&](double x, double y) {
      return 2 * x >= double(ox) && 2 * x <= double(ox + W) && 2 * y >= double(oy) && 2 * y <= double(oy + W);
    };
    std::ostringstream s;
    s << "gauge " << i << " (at " << cx << ", " << cy << " DBU): ";
    if (!(g.cd[i] > 0)) fail(s.str() + "its drawn cd is not positive");
    if (!(std::hypot(g.x2[i] - g.x1[i], g.y2[i] - g.y1[i]) > 0)) fail(s.str() + "its measurement line has no length");
    if (!inside(g.x1[i], g.y1[i]) || !inside(g.x2[i], g.y2[i])) {
      s << "its measurement line reaches outside its window, the model's period of " << P << " nm centred on the point";
      fail(s.str());
    }
  }
  // Who simulates: the first gauge of each (type, context); the others read its result.
  const Sources sources = sources_of(g.type, g.context);
  const std::vector<std::size_t>& source = sources.source;
  const std::vector<std::size_t>& reps = sources.reps;
  Printability out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.printed_cd.assign(n, nan);
  out.fails.assign(n, Fail::none);
  out.fails_nominal.assign(n, Fail::none);
  out.pv_band.assign(n, nan);
  out.score.assign(n, nan);
  out.simulations = reps.size();
  out.shared = n - reps.size();
  const Layer shapes(layer, std::max<std::int64_t>(W / 2, 1));
  const double reach = P / 4;
  // One condition's reading along a line: the printed width (NaN unless measured), the failure,
  // the per-condition score (printability.hpp), against threshold t.
  struct Reading {
    Fail fail = Fail::none;
    double width = std::numeric_limits<double>::quiet_NaN();
    double score = 0;
    bool open = false;
  };
  auto read = [&](const Cut& cut, const LineProfile& line, double t, bool space, double drawn) {
    Reading r;
    switch (cut.outcome) {
      case Cut::Outcome::measured:
        r.width = cut.width;
        r.score = cut.width / drawn;
        break;
      case Cut::Outcome::open:
        r.open = true;
        r.score = 2 * reach / drawn;
        break;
      case Cut::Outcome::pinch:
      case Cut::Outcome::bridge: {
        const double at = line.at(0);
        r.fail = space ? Fail::bridge : Fail::pinch;
        r.width = 0;
        r.score = space ? (at > 0 ? t / at - 1 : -1.0) : at / t - 1;
        break;
      }
    }
    return r;
  };
  const bool window = model.dose > 0;
  const double t = model.threshold;
  const double t_inner = t / ((1 - model.dose) * (1 - model.dose)), t_outer = t / ((1 + model.dose) * (1 + model.dose));
  const LineKernels focused(kernels);
  const std::unique_ptr<const LineKernels> defocused(model.defocus ? new LineKernels(*model.defocus) : nullptr);
  std::exception_ptr error;
  std::mutex error_lock;
  // Simulated gauges on one line (the same point and direction: a width gauge of each type
  // across one feature, say) share its window and profile, and are read each by its own type.
  // The lines in the order of their first gauge; lines[l]'s gauges are on_line[l].
  std::vector<std::size_t> lines;
  std::vector<std::vector<std::size_t>> on_line;
  {
    struct Key {
      double cx, cy, dx, dy;
      bool operator==(const Key& o) const { return cx == o.cx && cy == o.cy && dx == o.dx && dy == o.dy; }
    };
    struct Hash {
      std::size_t operator()(const Key& k) const {
        std::size_t h = 0;
        for (const double v : {k.cx, k.cy, k.dx, k.dy}) h = h * 1000003u ^ std::hash<double>()(v);
        return h;
      }
    };
    std::unordered_map<Key, std::size_t, Hash> line_of;
    for (const std::size_t i : reps) {
      const double dx = g.x2[i] - g.x1[i], dy = g.y2[i] - g.y1[i], len = std::hypot(dx, dy);
      const auto [at, fresh] = line_of.try_emplace(Key{g.cx[i], g.cy[i], dx / len, dy / len}, lines.size());
      if (fresh) lines.push_back(i), on_line.emplace_back();
      on_line[at->second].push_back(i);
    }
  }
  out.images = lines.size();
  // Lines go to the workers in blocks profiled together (LineProfile::batch: the kernels are
  // read once a block, not once a line).
  constexpr std::size_t kBlock = 16;
  detail::parallel_for((lines.size() + kBlock - 1) / kBlock, threads, [&](unsigned, std::size_t block) {
    try {
      const std::size_t first = block * kBlock, last = std::min(first + kBlock, lines.size());
      std::vector<MaskSpectrum> masks;
      masks.reserve(last - first);
      std::vector<Probe> probes;
      for (std::size_t l = first; l < last; ++l) {
        const std::size_t i = lines[l];
        const double cx = g.cx[i], cy = g.cy[i];
        const std::int64_t ox = origin(cx), oy = origin(cy);
        masks.emplace_back(shapes.clip(ox, oy, W), Window{{ox, oy}, half_dbu}, P, kernels.half());
        const double px = (2 * cx - double(ox)) * half_dbu, py = (2 * cy - double(oy)) * half_dbu;
        probes.push_back({&masks.back(), px, py, g.x2[i] - g.x1[i], g.y2[i] - g.y1[i]});
      }
      std::vector<const LineKernels*> sets{&focused};
      if (window && defocused) sets.push_back(defocused.get());
      std::vector<std::vector<LineProfile>> profiles = LineProfile::batch(sets, probes);
      for (std::vector<LineProfile>& set : profiles)
        for (LineProfile& line : set) line.blur(model.blur);
      const std::vector<LineProfile>& focus_lines = profiles[0];
      const std::vector<LineProfile>& defocus_lines = profiles.back();
      for (std::size_t l = first; l < last; ++l) {
        // A line's cuts, made on first use: [condition: nominal, outer, inner][space]. Gauges of
        // several types on one line read the same cuts; only their drawn cds differ.
        std::optional<Cut> cuts[3][2];
        const LineProfile& line = focus_lines[l - first];
        const LineProfile& blurred = window && defocused ? defocus_lines[l - first] : line;
        auto reading = [&](int condition, bool space, double drawn) {
          const LineProfile& on = condition == 2 ? blurred : line;
          const double at = condition == 0 ? t : condition == 1 ? t_outer : t_inner;
          std::optional<Cut>& cut = cuts[condition][space];
          if (!cut) cut = measure(on, at, space ? Across::clear : Across::printed, reach);
          return read(*cut, on, at, space, drawn);
        };
        for (const std::size_t i : on_line[l]) {
          const bool space = g.type[i] == kExternalGauge;
          const double drawn = g.cd[i] * dbu_nm;
          const Reading nominal = reading(0, space, drawn);
          if (nominal.fail == Fail::none) out.printed_cd[i] = nominal.width;  // a failure leaves NaN
          out.fails[i] = out.fails_nominal[i] = nominal.fail;
          out.score[i] = nominal.score;
          if (!window) continue;
          // The outer corner: in focus at the high dose, the same image against a lower threshold;
          // the inner corner: defocused at the low dose (the focus image for a dose-only window).
          const Reading outer = reading(1, space, drawn), inner = reading(2, space, drawn);
          for (const Reading* r : {&outer, &inner}) {
            if (r->fail != Fail::none) out.fails[i] = r->fail;
            out.score[i] = std::min(out.score[i], r->score);
          }
          if (!outer.open && !inner.open) out.pv_band[i] = std::abs(outer.width - inner.width);
        }
      }
    } catch (...) {
      const std::lock_guard<std::mutex> hold(error_lock);
      if (!error) error = std::current_exception();
    }
  });
  if (error) std::rethrow_exception(error);
  for (std::size_t i = 0; i < n; ++i)
    if (source[i] != i) {
      out.printed_cd[i] = out.printed_cd[source[i]];
      out.fails[i] = out.fails[source[i]];
      out.fails_nominal[i] = out.fails_nominal[source[i]];
      out.pv_band[i] = out.pv_band[source[i]];
      out.score[i] = out.score[source[i]];
    }
  return out;
}

std::vector<std::vector<double>> window_images(const FlatPolygons& layer, double dbu_nm, const std::vector<double>& cx,
                                               const std::vector<double>& cy, const Kernels& kernels, int m,
                                               int threads, double blur) {
  if (kernels.count() == 0) fail("the model has no kernels");
  if (!(dbu_nm > 0)) fail("the database unit must be positive");
  if (m < kernels.size) fail("a picture's grid must be at least the kernels' size");
  if (!(blur >= 0) || !std::isfinite(blur)) fail("the resist blur must be a number >= 0");
  if (cx.size() != cy.size()) fail("the centres' x and y have different lengths");
  const double P = kernels.period, half_dbu = dbu_nm / 2;
  const std::int64_t W = window_side(P, dbu_nm);
  const Layer shapes(layer, std::max<std::int64_t>(W / 2, 1));
  std::vector<std::vector<double>> out(cx.size());
  for (std::size_t k = 0; k < cx.size(); ++k) {
    const std::int64_t ox = window_origin(cx[k], W), oy = window_origin(cy[k], W);
    const AerialImage image(kernels, MaskSpectrum(shapes.clip(ox, oy, W), Window{{ox, oy}, half_dbu}, P, kernels.half()));
    out[k] = image.grid(m, threads);
    blur_grid(out[k], m, P, blur);
  }
  return out;
}

}  // namespace linf::litho
