#include "linf/gds.hpp"

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

namespace linf {
namespace {

// GDSII records: a big-endian 16-bit length (header included), a record type, a data type.
class Stream {
 public:
  explicit Stream(const std::string& path) : f_(std::fopen(path.c_str(), "wb"), &std::fclose), path_(path) {
    if (!f_) throw std::runtime_error("cannot write " + path);
    buf_.reserve(1 << 20);
  }
  void record(std::uint8_t type, std::uint8_t data, std::size_t bytes) {
    const std::size_t n = 4 + bytes;
    put16(std::uint16_t(n));
    buf_.push_back(char(type));
    buf_.push_back(char(data));
  }
  void put16(std::uint16_t v) { buf_.push_back(char(v >> 8)), buf_.push_back(char(v)); }
  void put32(std::int32_t v) {
    const auto u = std::uint32_t(v);
    for (int s = 24; s >= 0; s -= 8) buf_.push_back(char(u >> s));
  }
  // GDSII's 8-byte real: sign, excess-64 base-16 exponent, 56-bit mantissa in [1/16, 1).
  void put_real(double v) {
    std::uint64_t bits = 0;
    if (v != 0) {
      const bool neg = v < 0;
      v = std::fabs(v);
      int e = 64;
      while (v >= 1) v /= 16, ++e;
      while (v < 1.0 / 16) v *= 16, --e;
      const auto m = std::uint64_t(std::llround(std::ldexp(v, 56)));
      bits = (std::uint64_t(neg) << 63) | (std::uint64_t(e) << 56) | (m & ((std::uint64_t(1) << 56) - 1));
    }
    for (int s = 56; s >= 0; s -= 8) buf_.push_back(char(bits >> s));
  }
  void ints16(std::uint8_t type, std::initializer_list<std::int16_t> v) {
    record(type, 2, 2 * v.size());
    for (auto x : v) put16(std::uint16_t(x));
  }
  void text(std::uint8_t type, const std::string& s) {
    const std::size_t n = s.size() + (s.size() & 1);  // even length, NUL-padded
    record(type, 6, n);
    buf_.append(s);
    if (n != s.size()) buf_.push_back('\0');
  }
  void flush_if_full() {
    if (buf_.size() > (1 << 20) - 64) flush();
  }
  void close() {
    flush();
    if (std::ferror(f_.get()) || std::fflush(f_.get()) != 0) throw std::runtime_error("error writing " + path_);
  }

 private:
  void flush() {
    std::fwrite(buf_.data(), 1, buf_.size(), f_.get());
    buf_.clear();
  }
  std::unique_ptr<FILE, int (*)(FILE*)> f_;
  std::string path_;
  std::string buf_;
};

std::int32_t grid(double v) {
  const double r = std::nearbyint(v);  // ties to even, as Python's round()
  if (!(r >= double(INT32_MIN) && r <= double(INT32_MAX)))
    throw std::out_of_range("a diagram coordinate does not fit GDSII's 32 bits");
  return std::int32_t(r);
}

}  // namespace

DrawCounts write_pieces_gds(const Diagram& d, const GdsLayers& L, const std::string& path) {
  Stream s(path);
  const std::initializer_list<std::int16_t> date = {2026, 1, 1, 0, 0, 0, 2026, 1, 1, 0, 0, 0};
  s.ints16(0x00, {600});  // HEADER: version
  s.ints16(0x01, date);   // BGNLIB
  s.text(0x02, "LINF_OPC");
  s.record(0x03, 5, 16);  // UNITS: user units (um) per DBU, metres per DBU
  s.put_real(L.dbu);
  s.put_real(L.dbu * 1e-6);
  s.ints16(0x05, date);  // BGNSTR
  s.text(0x06, L.cell);
  DrawCounts n{};
  for (const Piece& p : d.pieces) {
    const std::int32_t x1 = grid(p.p.x), y1 = grid(p.p.y), x2 = grid(p.q.x), y2 = grid(p.q.y);
    if (x1 == x2 && y1 == y2) continue;
    const auto k = std::size_t(p.kind);
    s.record(0x09, 0, 0);  // PATH (width and path type default to 0)
    s.ints16(0x0D, {std::int16_t(L.layer)});
    s.ints16(0x0E, {std::int16_t(L.datatype[k])});
    s.record(0x10, 3, 16);  // XY
    s.put32(x1), s.put32(y1), s.put32(x2), s.put32(y2);
    s.record(0x11, 0, 0);  // ENDEL
    s.flush_if_full();
    ++n[k];
  }
  s.record(0x07, 0, 0);  // ENDSTR
  s.record(0x04, 0, 0);  // ENDLIB
  s.close();
  return n;
}

}  // namespace linf
