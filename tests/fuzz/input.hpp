// The fuzzer's input format, both ways: bytes -> a layout (decode, for the target) and records
// -> bytes (Writer, for the seed corpus). Every byte string decodes to some layout, so each of
// libFuzzer's mutations reaches the core; missing bytes read as 0.
//
//   byte 0   bits 0-1 style: rectilinear, octilinear, any angle, plain segments and points;
//            bit 2/3 mirror x/y; bit 4 the polygons are also sites of the farthest diagram
//            (else only one diagonal of each); bits 5-7 placement (kPlacements)
//   byte 1   bits 0-1 span of the local coordinates (kSpans); bits 2-7 v: the scale's power
//            of two, v - 32 where v >= 32 (so half the inputs are drawn at their own size)
//   byte 2   bits 0-2 the scale's odd factor (1 + 2 b); bit 3 tiled build, bits 4-5 tiles
//            across (2 + b), bit 6 no axis tie-break, bit 7 no far-field pass
//   placement  AtOrigin: none; InRange: offset x, y (int32 each, mod 2^30); AtLimit: a corner
//            byte, then slack x, y (a byte each, b - 2 DBU inside the limit, so b < 2 lies
//            just beyond it); Raw: offset x, y (int32 each), often beyond
//   records  up to kMaxRecords, each a kind byte (bits 0-1 type, bits 2-7 a count) and u16
//            values, little-endian. A coordinate is v % span, a length 1 + v % span.
//            box: x, y, w, h.  frame: a box and the width of its rim.
//            staircase: m = 2 + count % 5 x values then m y values, the rectilinear ring
//              (X0,Y0) (X1,Y0) (X1,Y1) ... (X0,Y[m-1]); octilinear and any angle: then one
//              45-degree corner cut a vertex (v % span - span / 2 where positive), as long as
//              the edges beside it leave room.
//            ring (any angle only, else a staircase): n = 3 + count % 6 points.
//            plain style: every record is an item x1, y1, x2, y2 (a point where they agree).
// World coordinates: offset + (mirror ? -1 : 1) * scale * local, in 64 bits, so they may fall
// outside +-2^30 on purpose: the core must then refuse the input.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf::fuzz {

enum Style { Rectilinear = 0, Octilinear = 1, AnyAngle = 2, Plain = 3 };
enum Placement { AtOrigin = 0, InRange = 1, AtLimit = 2, Raw = 3 };
enum Type { BoxType = 0, FrameType = 1, StaircaseType = 2, RingType = 3 };
constexpr int kMaxRecords = 10;
constexpr std::int64_t kSpans[4] = {64, 256, 4096, 65536};
constexpr int kPlacements[8] = {AtOrigin, AtOrigin, AtOrigin, AtOrigin, InRange, AtLimit, AtLimit, Raw};
constexpr std::int64_t kLimit = kCoordLimit;  // |x| < 2^30

struct Layout {
  int style = Rectilinear;
  bool polygon_sites = false;
  std::uint8_t options = 0;         // byte 2's bits 3-7, for the builder
  std::int64_t extent = 1;          // the world's larger side
  std::vector<Polygon> polygons;    // polygon styles
  std::vector<Segment> items;       // plain style: segments, and points where a == b
};

namespace detail {
struct Reader {
  const std::uint8_t* p;
  std::size_t n, i = 0;
  bool more() const { return i < n; }
  std::uint8_t u8() { return i < n ? p[i++] : 0; }
  std::uint16_t u16() { return std::uint16_t(u8() | (u8() << 8)); }
  std::int32_t i32() {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t(u8()) << (8 * k);
    return std::int32_t(v);
  }
};

// Cuts the corners of a ring (45 degrees in an axis-parallel corner), each by at most what the
// two edges beside it have left.
inline Ring cut_corners(const Ring& r, const std::vector<std::int64_t>& cuts) {
  const std::size_t n = r.size();
  std::vector<std::int64_t> left(n);  // edge i runs from r[i] to r[i + 1]
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = r[i];
    const Point& b = r[(i + 1) % n];
    left[i] = std::max(std::llabs(b.x - a.x), std::llabs(b.y - a.y));
  }
  Ring out;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t before = (i + n - 1) % n;
    const std::int64_t c = std::min({cuts[i], left[before], left[i]});
    if (c == 0) {
      out.push_back(r[i]);
      continue;
    }
    left[before] -= c, left[i] -= c;
    auto toward = [&](const Point& q) {
      return Point{r[i].x + (q.x > r[i].x) * c - (q.x < r[i].x) * c, r[i].y + (q.y > r[i].y) * c - (q.y < r[i].y) * c};
    };
    out.push_back(toward(r[before]));
    out.push_back(toward(r[(i + 1) % n]));
  }
  return out;
}
}  // namespace detail

inline Layout decode(const std::uint8_t* data, std::size_t size) {
  detail::Reader in{data, size};
  Layout L;
  const std::uint8_t head = in.u8(), span_scale = in.u8(), factor_options = in.u8();
  L.style = head & 3;
  L.polygon_sites = head & 16;
  L.options = factor_options >> 3;
  const std::int64_t span = kSpans[span_scale & 3];
  const std::int64_t factor = 1 + 2 * (factor_options & 7);
  int shift = std::max(0, (span_scale >> 2) - 32);
  while (shift > 0 && (2 * span * factor << shift) > (std::int64_t(1) << 33)) --shift;  // not all beyond
  const std::int64_t scale = factor << shift;
  const std::int64_t sx = head & 4 ? -scale : scale, sy = head & 8 ? -scale : scale;
  const int placement = kPlacements[head >> 5];
  std::int64_t ox = 0, oy = 0;
  int corner = 0, slack_x = 0, slack_y = 0;
  if (placement == InRange) ox = in.i32() % kLimit, oy = in.i32() % kLimit;
  if (placement == AtLimit) corner = in.u8(), slack_x = in.u8() - 2, slack_y = in.u8() - 2;
  if (placement == Raw) ox = in.i32(), oy = in.i32();

  auto coord = [&] { return std::int64_t(in.u16()) % span; };
  auto length = [&] { return 1 + std::int64_t(in.u16()) % span; };
  std::vector<Polygon> local;
  for (int k = 0; k < kMaxRecords && in.more(); ++k) {
    const std::uint8_t kind = in.u8();
    const int count = kind >> 2;
    int type = kind & 3;
    if (L.style == Plain) {
      const std::int64_t x1 = coord(), y1 = coord(), x2 = coord(), y2 = coord();
      L.items.push_back({{x1, y1}, {x2, y2}});
      continue;
    }
    if (type == RingType && L.style != AnyAngle) type = StaircaseType;
    Polygon p;
    if (type == BoxType || type == FrameType) {
      const std::int64_t x = coord(), y = coord(), w = length(), h = length();
      p.outer = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
      const std::int64_t t = type == FrameType ? length() : 0;
      if (type == FrameType && 2 * t < std::min(w, h))
        p.holes.push_back({{x + t, y + t}, {x + w - t, y + t}, {x + w - t, y + h - t}, {x + t, y + h - t}});
    } else if (type == StaircaseType) {
      const int m = 2 + count % 5;
      std::vector<std::int64_t> X(m), Y(m);
      for (auto& v : X) v = coord();
      for (auto& v : Y) v = coord();
      for (int i = 0; i < m; ++i) p.outer.push_back({X[i], Y[i]}), p.outer.push_back({X[(i + 1) % m], Y[i]});
      if (L.style != Rectilinear) {
        std::vector<std::int64_t> cuts(p.outer.size());
        for (auto& c : cuts) c = std::max<std::int64_t>(0, coord() - span / 2);
        p.outer = detail::cut_corners(p.outer, cuts);
      }
    } else {
      const int n = 3 + count % 6;
      for (int i = 0; i < n; ++i) {
        const std::int64_t x = coord(), y = coord();
        p.outer.push_back({x, y});
      }
    }
    local.push_back(p);
  }

  // Scale and mirror, then place: against the limit, the far side of the layout from the
  // origin lies `slack` inside it.
  auto scaled = [&](Point q) { return Point{sx * q.x, sy * q.y}; };
  std::int64_t x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  bool first = true;
  auto grow = [&](const Point& q) {
    if (first) x1 = x2 = q.x, y1 = y2 = q.y, first = false;
    x1 = std::min(x1, q.x), x2 = std::max(x2, q.x), y1 = std::min(y1, q.y), y2 = std::max(y2, q.y);
  };
  for (Polygon& p : local) {
    for (Point& q : p.outer) grow(q = scaled(q));
    for (Ring& h : p.holes)
      for (Point& q : h) q = scaled(q);
  }
  for (Segment& s : L.items) grow(s.a = scaled(s.a)), grow(s.b = scaled(s.b));
  L.extent = std::max<std::int64_t>({1, x2 - x1, y2 - y1});
  if (placement == AtLimit) {
    ox = corner & 1 ? kLimit - 1 - slack_x - x2 : -(kLimit - 1 - slack_x) - x1;
    oy = corner & 2 ? kLimit - 1 - slack_y - y2 : -(kLimit - 1 - slack_y) - y1;
  }
  auto place = [&](Point& q) { q.x += ox, q.y += oy; };
  for (Polygon& p : local) {
    for (Point& q : p.outer) place(q);
    for (Ring& h : p.holes)
      for (Point& q : h) place(q);
  }
  for (Segment& s : L.items) place(s.a), place(s.b);
  L.polygons = std::move(local);
  return L;
}

// Writes inputs record by record (the seed corpus); the caller keeps to the format above.
struct Writer {
  std::vector<std::uint8_t> bytes;
  void u8(int v) { bytes.push_back(std::uint8_t(v)); }
  void u16(std::int64_t v) { u8(int(v & 255)), u8(int((v >> 8) & 255)); }
  void i32(std::int64_t v) {
    for (int k = 0; k < 4; ++k) u8(int((std::uint64_t(v) >> (8 * k)) & 255));
  }
};

}  // namespace linf::fuzz
