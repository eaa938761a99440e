// Reading SOCS kernels from the ICCAD 2013 files (see kernels.hpp for the format).
#include "linf/litho/kernels.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace linf::litho {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument("kernel file " + path + ": " + what);
}

std::uint32_t big_endian_word(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | std::uint32_t(p[3]);
}

float big_endian_float(const unsigned char* p) {
  const std::uint32_t w = big_endian_word(p);
  float f;
  std::memcpy(&f, &w, sizeof f);
  return f;
}

std::vector<double> read_weights(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot be read");
  std::vector<double> numbers;
  std::string word;
  while (in >> word) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.size() || !std::isfinite(v)) fail(path, "'" + word + "' is not a number");
    numbers.push_back(v);
  }
  if (numbers.empty()) fail(path, "is empty; it must hold the kernel count, then one weight a kernel");
  const double count = numbers[0];
  if (count < 1 || count != std::floor(count) || count > 10000)
    fail(path, "its first number must be the kernel count, a positive integer");
  if (numbers.size() - 1 != std::size_t(count)) {
    std::ostringstream s;
    s << "says " << std::size_t(count) << " kernels but lists " << numbers.size() - 1 << " weights";
    fail(path, s.str());
  }
  for (std::size_t i = 1; i < numbers.size(); ++i)
    if (numbers[i] < 0) fail(path, "holds a negative weight");
  return std::vector<double>(numbers.begin() + 1, numbers.end());
}

std::vector<std::complex<double>> read_kernel(const std::string& path, int& size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot be read");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 24) fail(path, "is shorter than its 24-byte header");
  const std::int32_t nx = std::int32_t(big_endian_word(&bytes[0])), ny = std::int32_t(big_endian_word(&bytes[4]));
  const std::int32_t parts = std::int32_t(big_endian_word(&bytes[8]));
  if (nx != ny || nx < 1 || nx % 2 == 0 || nx > 4095 || parts != 2) {
    std::ostringstream s;
    s << "has the header (" << nx << ", " << ny << ", " << parts
      << ", ...); a kernel is n x n complex values, n odd: (n, n, 2, ...)";
    fail(path, s.str());
  }
  const std::size_t n = std::size_t(nx), want = 24 + n * n * 8;
  if (bytes.size() != want) {
    std::ostringstream s;
    s << "has " << bytes.size() << " bytes; its header (" << n << " x " << n << ") needs " << want;
    fail(path, s.str());
  }
  if (size != 0 && size != nx) fail(path, "is of another size than the kernels before it");
  size = nx;
  std::vector<std::complex<double>> values(n * n);
  for (std::size_t j = 0; j < n * n; ++j) {
    const float re = big_endian_float(&bytes[24 + 8 * j]), im = big_endian_float(&bytes[28 + 8 * j]);
    if (!std::isfinite(re) || !std::isfinite(im)) fail(path, "holds a value that is not a finite number");
    values[j] = {re, im};
  }
  return values;
}

}  // namespace

double Kernels::clear_field() const {
  double sum = 0;
  for (std::size_t i = 0; i < count(); ++i) sum += weights[i] * std::norm(at(i, 0, 0));
  return sum;
}

Kernels read_kernels(const std::string& folder, double period) {
  if (!(period > 0)) throw std::invalid_argument("the kernels' period must be positive");
  Kernels k;
  k.period = period;
  const std::string base = folder.empty() || folder.back() == '/' ? folder : folder + "/";
  k.weights = read_weights(base + "scales.txt");
  for (std::size_t i = 0; i < k.weights.size(); ++i)
    k.values.push_back(read_kernel(base + "fh" + std::to_string(i) + ".bin", k.size));
  return k;
}

}  // namespace linf::litho
