#include "linf/io/gds.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <utility>

namespace linf {

// GDSII records: a big-endian 16-bit length (header included), a record type, a data type.
struct GdsWriter::Stream {
  std::unique_ptr<FILE, int (*)(FILE*)> f;
  std::string path, buf;

  explicit Stream(const std::string& p) : f(std::fopen(p.c_str(), "wb"), &std::fclose), path(p) {
    if (!f) throw std::runtime_error("cannot write " + p);
    buf.reserve(1 << 20);
  }
  void record(std::uint8_t type, std::uint8_t data, std::size_t bytes) {
    put16(std::uint16_t(4 + bytes));
    buf.push_back(char(type));
    buf.push_back(char(data));
  }
  void put16(std::uint16_t v) { buf.push_back(char(v >> 8)), buf.push_back(char(v)); }
  void put32(std::int32_t v) {
    const auto u = std::uint32_t(v);
    for (int s = 24; s >= 0; s -= 8) buf.push_back(char(u >> s));
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
    for (int s = 56; s >= 0; s -= 8) buf.push_back(char(bits >> s));
  }
  void ints16(std::uint8_t type, std::initializer_list<int> v) {
    record(type, 2, 2 * v.size());
    for (int x : v) put16(std::uint16_t(x));
  }
  void string(std::uint8_t type, const std::string& s) {
    const std::size_t n = s.size() + (s.size() & 1);  // even length, NUL-padded
    record(type, 6, n);
    buf.append(s);
    if (n != s.size()) buf.push_back('\0');
  }
  void layer(std::uint8_t element, int layer, std::uint8_t type_record, int type) {
    record(element, 0, 0);
    ints16(0x0D, {layer});
    ints16(type_record, {type});
  }
  void flush() {
    std::fwrite(buf.data(), 1, buf.size(), f.get());
    buf.clear();
  }
  void flush_if_full() {
    if (buf.size() > (1 << 20) - 256) flush();
  }
};

namespace {

std::int32_t grid(double v) {
  const double r = std::nearbyint(v);  // ties to even, as Python's round()
  if (!(r >= double(INT32_MIN) && r <= double(INT32_MAX)))
    throw std::out_of_range("a coordinate does not fit GDSII's 32 bits");
  return std::int32_t(r);
}

constexpr std::initializer_list<int> kDate = {2026, 1, 1, 0, 0, 0, 2026, 1, 1, 0, 0, 0};

}  // namespace

bool cut_to_drawable(double& x1, double& y1, double& x2, double& y2) {
  const double L = kDrawLimit;
  if (std::fabs(x1) <= L && std::fabs(y1) <= L && std::fabs(x2) <= L && std::fabs(y2) <= L) return true;
  // Liang-Barsky: the part of x1 + t dx, y1 + t dy, t in [0, 1], inside the square.
  const double dx = x2 - x1, dy = y2 - y1;
  double t0 = 0, t1 = 1;
  for (const auto& [p, q] : {std::pair{-dx, x1 + L}, std::pair{dx, L - x1}, std::pair{-dy, y1 + L}, std::pair{dy, L - y1}}) {
    if (p == 0) {
      if (q < 0) return false;  // parallel to this side and beyond it
      continue;
    }
    const double r = q / p;
    if (p < 0) {
      if (r > t1) return false;
      t0 = std::max(t0, r);
    } else {
      if (r < t0) return false;
      t1 = std::min(t1, r);
    }
  }
  // The ends on the square's sides, exactly: rounding in t must not take them past it.
  auto in = [L](double v) { return std::clamp(v, -L, L); };
  const double ax = in(x1 + t0 * dx), ay = in(y1 + t0 * dy), bx = in(x1 + t1 * dx), by = in(y1 + t1 * dy);
  x1 = ax, y1 = ay, x2 = bx, y2 = by;
  return true;
}

GdsWriter::GdsWriter(const std::string& path, double dbu, const std::string& cell)
    : s_(std::make_unique<Stream>(path)) {
  s_->ints16(0x00, {600});  // HEADER: version
  s_->ints16(0x01, kDate);  // BGNLIB
  s_->string(0x02, "LINF_OPC");
  s_->record(0x03, 5, 16);  // UNITS: user units (um) per DBU, metres per DBU
  s_->put_real(dbu);
  s_->put_real(dbu * 1e-6);
  s_->ints16(0x05, kDate);  // BGNSTR
  s_->string(0x06, cell);
}

GdsWriter::~GdsWriter() = default;

bool GdsWriter::path(int layer, int datatype, double x1, double y1, double x2, double y2) {
  if (!cut_to_drawable(x1, y1, x2, y2)) return false;
  const std::int32_t v[4] = {grid(x1), grid(y1), grid(x2), grid(y2)};
  s_->layer(0x09, layer, 0x0E, datatype);  // PATH, LAYER, DATATYPE (width and path type 0)
  s_->record(0x10, 3, 16);                 // XY
  for (std::int32_t c : v) s_->put32(c);
  s_->record(0x11, 0, 0);  // ENDEL
  s_->flush_if_full();
  return true;
}

void GdsWriter::text(int layer, int datatype, double x, double y, const std::string& str) {
  const std::int32_t px = grid(x), py = grid(y);
  s_->layer(0x0C, layer, 0x16, datatype);  // TEXT, LAYER, TEXTTYPE
  s_->record(0x10, 3, 8);                  // XY
  s_->put32(px), s_->put32(py);
  s_->string(0x19, str);   // STRING
  s_->record(0x11, 0, 0);  // ENDEL
  s_->flush_if_full();
}

void GdsWriter::close() {
  s_->record(0x07, 0, 0);  // ENDSTR
  s_->record(0x04, 0, 0);  // ENDLIB
  s_->flush();
  if (std::ferror(s_->f.get()) || std::fflush(s_->f.get()) != 0) throw std::runtime_error("error writing " + s_->path);
}

void draw_pieces(GdsWriter& w, const GdsLayers& L, const Piece* pieces, std::size_t n, DrawCounts& drawn) {
  for (std::size_t i = 0; i < n; ++i) {
    const Piece& p = pieces[i];
    double x1 = p.p.x, y1 = p.p.y, x2 = p.q.x, y2 = p.q.y;
    if (!cut_to_drawable(x1, y1, x2, y2)) continue;
    if (grid(x1) == grid(x2) && grid(y1) == grid(y2)) continue;
    const auto k = std::size_t(p.kind);
    w.path(L.layer, L.datatype[k], x1, y1, x2, y2);
    ++drawn[k];
  }
}

DrawCounts write_pieces_gds(const Diagram& d, const GdsLayers& L, const std::string& path) {
  GdsWriter w(path, L.dbu, L.cell);
  DrawCounts n{};
  draw_pieces(w, L, d.pieces.data(), d.pieces.size(), n);
  w.close();
  return n;
}

}  // namespace linf
