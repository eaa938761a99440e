// SOCS kernels from optics (optics.hpp): the TCC of an annular (or conventional, or coherent)
// source and a defocused circular pupil, decomposed into its largest coherent kernels.
#include "linf/litho/optics.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace linf::litho {
namespace {

using cd = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

void check(const Optics& o) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("optics: " + what); };
  std::ostringstream v;
  if (!(o.wavelength > 0)) bad("the wavelength must be positive");
  if (!(o.na > 0)) bad("the numerical aperture must be positive");
  if (!(o.medium >= 1)) bad("the medium's refractive index must be at least 1");
  if (!(o.na < o.medium)) {
    v << "a numerical aperture of " << o.na << " needs immersion: it must be below the medium's index ("
      << o.medium << (o.medium == 1 ? ", dry)" : ")");
    bad(v.str());
  }
  if (!(o.sigma_in >= 0) || !(o.sigma_out >= 0)) bad("sigma must not be negative");
  if (o.sigma_in > o.sigma_out) bad("the inner sigma must not exceed the outer sigma");
  if (o.sigma_out > 1) bad("the outer sigma must not exceed 1 (the source must fit in the pupil)");
  if (!(o.period > 0)) bad("the period must be positive");
  if (!std::isfinite(o.defocus)) bad("the defocus must be a number");
  if (o.kernels < 1) bad("at least one kernel is needed");
  if (!(o.quasar_opening >= 0 && o.quasar_opening <= 90)) bad("the quasar opening must be between 0 and 90 degrees");
}

}  // namespace

Optics optics_preset(const std::string& name) {
  Optics o;
  if (name == "duv193") return o;  // the defaults: 193 nm, NA 1.35 in water, annular 0.7 / 0.9
  if (name == "euv") {
    o.wavelength = 13.5;
    o.na = 0.33;
    o.medium = 1;
    o.sigma_in = 0.5;
    o.sigma_out = 0.9;
    o.period = 512;
    return o;
  }
  throw std::invalid_argument("optics: unknown preset '" + name + "' (duv193, euv)");
}

Kernels kernels_from_optics(const Optics& o) {
  check(o);
  // Frequencies in units of 1 / period: the pupil's radius r, the source's radii.
  const double r = o.na * o.period / o.wavelength, eps = 1e-9;
  const int h = int(std::floor(r * (1 + o.sigma_out) + eps));
  const int n = 2 * h + 1;
  std::vector<std::pair<int, int>> source;
  const int reach = int(std::floor(o.sigma_out * r + eps));
  for (int jx = -reach; jx <= reach; ++jx)
    for (int jy = -reach; jy <= reach; ++jy) {
      const double d = std::hypot(double(jx), double(jy));
      if (!(d <= o.sigma_out * r + eps && d >= o.sigma_in * r - eps)) continue;
      if (o.quasar_opening > 0 && d > 0) {
        // The angle from the nearest diagonal, folded into [0, 45] degrees.
        const double angle = std::atan2(std::abs(double(jy)), std::abs(double(jx))) * 180 / kPi;
        if (std::abs(angle - 45) > o.quasar_opening / 2 + eps) continue;
      }
      source.push_back({jx, jy});
    }
  if (source.empty()) {
    std::ostringstream s;
    s << "optics: no source point between sigma " << o.sigma_in << " and " << o.sigma_out
      << (o.quasar_opening > 0 ? " in the quasar's poles" : "") << " on a period of "
      << o.period << " nm (the source is sampled every " << o.wavelength / (o.na * o.period) << " in sigma)";
    throw std::invalid_argument(s.str());
  }
  // A: one column a source point, its pupil shifted onto the frequency grid, times sqrt(1 / N).
  // A column is nonzero on its pupil's disc only (a fifth of the grid for euv): kept as the
  // list of its rows and values, for the Gram matrix below.
  const double k_medium = o.medium / o.wavelength;
  const double amplitude = 1 / std::sqrt(double(source.size()));
  const Eigen::Index rows = Eigen::Index(n) * n, columns = Eigen::Index(source.size());
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(rows, columns);
  std::vector<std::vector<std::pair<Eigen::Index, cd>>> disc(source.size());
  for (std::size_t s = 0; s < source.size(); ++s)
    for (int kx = -h; kx <= h; ++kx)
      for (int ky = -h; ky <= h; ++ky) {
        const double fx = kx + source[s].first, fy = ky + source[s].second;
        const double f2 = fx * fx + fy * fy;
        if (f2 > r * r * (1 + eps)) continue;
        const double f_nm2 = f2 / (o.period * o.period);
        const double phase = 2 * kPi * o.defocus * (std::sqrt(k_medium * k_medium - f_nm2) - k_medium);
        const Eigen::Index row = Eigen::Index(kx + h) * n + (ky + h);
        a(row, Eigen::Index(s)) = amplitude * std::polar(1.0, phase);
        disc[s].push_back({row, a(row, Eigen::Index(s))});
      }
  // T = A A^H has A^H A's nonzero eigenvalues; its eigenvectors are A v / sqrt(lambda). The
  // Gram matrix A^H A is Hermitian and each entry a sum over two discs' overlap: its upper
  // triangle from the discs (0.17 -> 0.03 s for euv against the dense product, measured).
  Eigen::MatrixXcd gram(columns, columns);
  std::vector<cd> column(static_cast<std::size_t>(rows), cd(0));
  for (Eigen::Index s = 0; s < columns; ++s) {
    for (const auto& [row, v] : disc[std::size_t(s)]) column[std::size_t(row)] = std::conj(v);
    for (Eigen::Index t = s; t < columns; ++t) {
      cd sum = 0;
      for (const auto& [row, v] : disc[std::size_t(t)]) sum += column[std::size_t(row)] * v;
      gram(s, t) = sum;
      gram(t, s) = std::conj(sum);
    }
    for (const auto& [row, v] : disc[std::size_t(s)]) column[std::size_t(row)] = 0;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(gram);
  if (eig.info() != Eigen::Success) throw std::runtime_error("optics: the eigen-decomposition failed");
  const Eigen::VectorXd& values = eig.eigenvalues();  // ascending
  const Eigen::Index total = values.size();
  const double top = values(total - 1);
  Eigen::Index keep = 0;
  while (keep < total && keep < o.kernels && values(total - 1 - keep) > 1e-12 * top) ++keep;
  // Never split a group of equal weights (x- and y-like kernels): the image would lose the
  // source's symmetry. Drop the kept tail that equals the first weight left out.
  if (keep < total) {
    const double first_out = values(total - 1 - keep);
    while (keep > 1 && std::abs(values(total - keep) - first_out) <= 1e-9 * top) --keep;
  }
  Kernels k;
  k.size = n;
  k.period = o.period;
  for (Eigen::Index i = 0; i < keep; ++i) {
    const double lambda = values(total - 1 - i);
    const Eigen::VectorXcd u = a * eig.eigenvectors().col(total - 1 - i) / std::sqrt(lambda);
    k.weights.push_back(lambda);
    k.values.emplace_back(u.data(), u.data() + u.size());
  }
  // With every kernel a clear field images to sum of the source's weights = 1; the kernels
  // left out take a little of it: scale the weights back so that it is exactly 1.
  const double clear = k.clear_field();
  for (double& w : k.weights) w /= clear;
  return k;
}

}  // namespace linf::litho
