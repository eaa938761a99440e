// The other kind's gauges on a grid of cells of side `radius`, each cell's in ascending cd (ties
// by index, so the result is one whatever the sort): a query reads the 3 x 3 cells around its
// point, each until a cd can no longer improve on the best found.
#include "linf/gauges/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "util/parallel.hpp"

namespace linf {

namespace {

struct CellKey {
  std::int64_t x, y;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return std::size_t(std::uint64_t(k.x) * 0x9E3779B97F4A7C15ull ^ (std::uint64_t(k.y) + 0x632BE59BD9B4E019ull));
  }
};
using Grid = std::unordered_map<CellKey, std::vector<std::int32_t>, CellHash>;

}  // namespace

std::vector<double> neighbouring_spaces(const std::vector<SpacePoint>& g, const std::vector<std::int32_t>& asked,
                                        double radius, int threads) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("the neighbour radius must be positive");
  for (std::int32_t i : asked)
    if (i < 0 || std::size_t(i) >= g.size()) throw std::invalid_argument("a gauge index out of range");
  auto cell = [&](double x, double y) { return CellKey{std::int64_t(std::floor(x / radius)), std::int64_t(std::floor(y / radius))}; };
  Grid grids[2];  // [0]: internal gauges, [1]: external gauges
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g[i].type == GaugeType::Internal || g[i].type == GaugeType::External)
      grids[g[i].type == GaugeType::External][cell(g[i].x, g[i].y)].push_back(std::int32_t(i));
  for (Grid& grid : grids)
    for (auto& [key, members] : grid)
      std::sort(members.begin(), members.end(), [&](std::int32_t a, std::int32_t b) {
        return g[std::size_t(a)].cd < g[std::size_t(b)].cd || (g[std::size_t(a)].cd == g[std::size_t(b)].cd && a < b);
      });
  const double reach = radius + 1e-9;  // a point on the square's border is in
  std::vector<double> out(asked.size(), std::numeric_limits<double>::quiet_NaN());
  constexpr std::size_t kBatch = 1024;
  detail::parallel_for((asked.size() + kBatch - 1) / kBatch, threads, [&](unsigned, std::size_t b) {
    for (std::size_t q = b * kBatch; q < std::min(asked.size(), (b + 1) * kBatch); ++q) {
      const SpacePoint& p = g[std::size_t(asked[q])];
      const Grid& grid = grids[p.type != GaugeType::External];
      const CellKey c = cell(p.x, p.y);
      double best = std::numeric_limits<double>::infinity();
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          const auto it = grid.find({c.x + dx, c.y + dy});
          if (it == grid.end()) continue;
          for (std::int32_t j : it->second) {
            const SpacePoint& o = g[std::size_t(j)];
            if (o.cd >= best) break;
            if (std::fabs(o.x - p.x) <= reach && std::fabs(o.y - p.y) <= reach) {
              best = o.cd;
              break;
            }
          }
        }
      if (best < std::numeric_limits<double>::infinity()) out[q] = best;
    }
  });
  return out;
}

}  // namespace linf
