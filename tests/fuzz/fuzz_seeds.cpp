// Writes the seed corpus (tests/fuzz/corpus/) in the fuzzer's input format (input.hpp): the
// inputs of the regression tests (CGAL's failing cases, the farthest diagram's tight and
// degenerate examples, drawn random layouts), each at the origin, against the +-2^30 limit,
// scaled up, and just beyond the limit. Every polygon input is decoded again and compared.
//   build-fuzz/fuzz_seeds tests/fuzz/corpus
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "input.hpp"
#include "layouts.hpp"

using namespace linf;
using namespace linf::fuzz;

namespace {

struct Frame {  // how an input is scaled and placed (header bytes 0-2 and the placement bytes)
  int placement = AtOrigin;
  int span = 2;                // index into kSpans
  int shift = 0, factor = 0;   // scale (1 + 2 factor) << shift
  bool mirror_x = false, mirror_y = false, polygon_sites = false;
  std::int64_t ox = 0, oy = 0;  // InRange
  int corner = 3, slack = 0;    // AtLimit: slack < 0 lies beyond the limit
  int options = 0;              // the builder's (byte 2, bits 3-7)
};

void header(Writer& w, int style, const Frame& f) {
  const int placement = f.placement == AtOrigin ? 0 : f.placement == InRange ? 4 : f.placement == AtLimit ? 5 : 7;
  w.u8(style | f.mirror_x << 2 | f.mirror_y << 3 | f.polygon_sites << 4 | placement << 5);
  w.u8(f.span | (f.shift ? 32 + f.shift : 0) << 2);
  w.u8(f.factor | f.options << 3);
  if (f.placement == InRange) w.i32(f.ox), w.i32(f.oy);
  if (f.placement == AtLimit) w.u8(f.corner), w.u8(f.slack + 2), w.u8(f.slack + 2);
}

bool rectilinear(const Ring& r) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point& a = r[i];
    const Point& b = r[(i + 1) % r.size()];
    if (a.x != b.x && a.y != b.y) return false;
  }
  return r.size() % 2 == 0;
}

// One polygon as a record, local coordinates relative to (ox, oy).
void record(Writer& w, int style, const Polygon& p, std::int64_t ox, std::int64_t oy, std::int64_t span) {
  std::int64_t x1 = p.outer[0].x, y1 = p.outer[0].y, x2 = x1, y2 = y1;
  for (const Point& q : p.outer)
    x1 = std::min(x1, q.x), x2 = std::max(x2, q.x), y1 = std::min(y1, q.y), y2 = std::max(y2, q.y);
  if (!p.holes.empty() || (p.outer.size() == 4 && rectilinear(p.outer))) {  // box, frame
    w.u8(p.holes.empty() ? BoxType : FrameType);
    w.u16(x1 - ox), w.u16(y1 - oy), w.u16(x2 - x1 - 1), w.u16(y2 - y1 - 1);
    if (!p.holes.empty()) w.u16(p.holes[0][0].x - x1 - 1);
  } else if (rectilinear(p.outer) && p.outer.size() <= 12) {  // staircase
    Ring r = p.outer;
    if (r[0].y != r[1].y) std::rotate(r.begin(), r.begin() + 1, r.end());
    const int m = int(r.size() / 2);
    w.u8(StaircaseType | (m - 2) << 2);
    for (int i = 0; i < m; ++i) w.u16(r[2 * i].x - ox);
    for (int i = 0; i < m; ++i) w.u16(r[2 * i].y - oy);
    if (style != Rectilinear)
      for (std::size_t i = 0; i < r.size(); ++i) w.u16(0);
  } else if (style == Octilinear && p.outer.size() == 8) {  // layouts.hpp's octagon: a cut box
    const std::int64_t c = p.outer[0].x - x1;
    w.u8(StaircaseType);
    w.u16(x1 - ox), w.u16(x2 - ox), w.u16(y1 - oy), w.u16(y2 - oy);
    for (int i = 0; i < 4; ++i) w.u16(c + span / 2);
  } else if (style == AnyAngle && p.outer.size() <= 8) {
    w.u8(RingType | int(p.outer.size() - 3) << 2);
    for (const Point& q : p.outer) w.u16(q.x - ox), w.u16(q.y - oy);
  } else {
    throw std::logic_error("no record for this polygon");
  }
}

// A ring from its least vertex, counter-clockwise: the same polygon compares equal.
Ring canonical(Ring r) {
  std::int64_t area = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point& a = r[i];
    const Point& b = r[(i + 1) % r.size()];
    area += a.x * b.y - a.y * b.x;
  }
  if (area < 0) std::reverse(r.begin(), r.end());
  std::rotate(r.begin(), std::min_element(r.begin(), r.end()), r.end());
  return r;
}

bool same(const std::vector<Polygon>& a, const std::vector<Polygon>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (canonical(a[i].outer) != canonical(b[i].outer) || a[i].holes.size() != b[i].holes.size()) return false;
    for (std::size_t k = 0; k < a[i].holes.size(); ++k)
      if (canonical(a[i].holes[k]) != canonical(b[i].holes[k])) return false;
  }
  return true;
}

std::vector<std::uint8_t> polygons(int style, const std::vector<Polygon>& ps, Frame f) {
  std::int64_t ox = ps[0].outer[0].x, oy = ps[0].outer[0].y;
  for (const Polygon& p : ps)
    for (const Point& q : p.outer) ox = std::min(ox, q.x), oy = std::min(oy, q.y);
  if (f.placement == AtOrigin) f.placement = InRange, f.ox = ox, f.oy = oy;  // as drawn
  Writer w;
  header(w, style, f);
  for (const Polygon& p : ps) record(w, style, p, ox, oy, kSpans[f.span]);
  if (f.placement <= InRange && f.shift == 0 && f.factor == 0 && !f.mirror_x && !f.mirror_y &&
      !same(decode(w.bytes.data(), w.bytes.size()).polygons, ps))
    throw std::logic_error("a polygon input does not decode to its layout");
  return w.bytes;
}

std::vector<std::uint8_t> items(const std::vector<Segment>& segs, Frame f) {
  std::int64_t ox = segs[0].a.x, oy = segs[0].a.y;
  for (const Segment& s : segs) ox = std::min({ox, s.a.x, s.b.x}), oy = std::min({oy, s.a.y, s.b.y});
  if (f.placement == AtOrigin) f.placement = InRange, f.ox = ox, f.oy = oy;  // as drawn
  f.span = 3;
  Writer w;
  header(w, Plain, f);
  for (const Segment& s : segs) w.u8(0), w.u16(s.a.x - ox), w.u16(s.a.y - oy), w.u16(s.b.x - ox), w.u16(s.b.y - oy);
  return w.bytes;
}

// The frames each regression input is written in: as drawn, against the limit (mirrored into
// the other corner), scaled up towards it, scaled against it, and one DBU beyond it.
std::vector<std::pair<std::string, Frame>> frames() {
  Frame origin, limit, far_corner, big, big_limit, beyond;
  limit.placement = far_corner.placement = big_limit.placement = beyond.placement = AtLimit;
  far_corner.corner = 0, far_corner.mirror_x = true;
  big.shift = 17, big.factor = 1;  // 3 << 17
  big_limit.shift = 12, big_limit.factor = 2, big_limit.corner = 2, big_limit.mirror_y = true;
  beyond.slack = -1, beyond.corner = 1;
  return {{"origin", origin}, {"limit", limit},          {"far-corner", far_corner},
          {"scaled", big},    {"scaled-limit", big_limit}, {"beyond", beyond}};
}

std::vector<Segment> segs(std::initializer_list<std::array<Coord, 4>> l) {
  std::vector<Segment> s;
  for (auto& g : l) s.push_back({{g[0], g[1]}, {g[2], g[3]}});
  return s;
}

void put(const std::string& dir, const std::string& name, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(dir + "/" + name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  std::printf("%-36s %3zu bytes\n", name.c_str(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIRECTORY\n");
    return 2;
  }
  const std::string dir = argv[1];
  // tests/cpp/diagram/test_reproducers.cpp: CGAL 5.5.1 fails on these.
  const auto case1 = segs({{210, 52, 585, 52}, {245, 12, 245, 20}, {390, 0, 0, 0}});
  const auto case2 =
      segs({{10025, 280, 10400, 280}, {10060, 240, 10060, 248}, {10205, 228, 9815, 228}, {8115, 280, 8115, 288}});
  for (const auto& [where, f] : frames()) {
    put(dir, "cgal-case1-" + where, items(case1, f));
    put(dir, "cgal-case2-" + where, items(case2, f));
  }
  const std::vector<Polygon> case3{{{{810, 924}, {1147, 924}, {1147, 964}, {810, 964}}, {}},
                                   {{{1210, 810}, {1210, 903}, {1317, 1010}, {1517, 1010}, {1517, 917}, {1410, 810}}, {}}};
  auto write_case3 = [](const Frame& f) {  // the hexagon is a box with two corners cut
    Writer w;
    header(w, Octilinear, f);
    w.u8(BoxType), w.u16(0), w.u16(924 - 810), w.u16(1147 - 810 - 1), w.u16(964 - 924 - 1);
    w.u8(StaircaseType), w.u16(1210 - 810), w.u16(1517 - 810), w.u16(0), w.u16(1010 - 810);
    for (int c : {0, 107, 0, 107}) w.u16(c ? c + kSpans[2] / 2 : 0);
    return w.bytes;
  };
  for (auto [where, f] : frames()) {
    f.polygon_sites = where == "origin";
    if (f.placement == AtOrigin) f.placement = InRange, f.ox = f.oy = 810;
    put(dir, "cgal-case3-" + where, write_case3(f));
    if (where == "origin" && !same(decode(write_case3(f).data(), write_case3(f).size()).polygons, case3))
      throw std::logic_error("case 3 does not decode to its polygons");
  }

  // tests/cpp/farthest/test_farthest.cpp: five faces for one segment, n + 8 faces, a plus sign,
  // segments on one line, crossing through one point with a repeated segment.
  put(dir, "farthest-five-faces", items(segs({{90, -60, -58, 24}, {-40, -27, 80, 24}, {84, 35, -80, -64}}), {}));
  put(dir, "farthest-n-plus-8", items(segs({{42, 79, -27, -52}, {-84, -54, 172, 130}, {56, -100, -24, 52},
                                            {100, -61, -71, 73}, {18, -9, -32, 65}, {-50, 152, 26, -84}}), {}));
  put(dir, "farthest-plus", items(segs({{0, 50, 100, 50}, {50, 0, 50, 100}}), {}));
  put(dir, "farthest-line", items(segs({{0, 10, 40, 10}, {100, 10, 160, 10}}), {}));
  put(dir, "farthest-star", items(segs({{0, 0, 100, 100}, {0, 100, 100, 0}, {50, 0, 50, 100}, {0, 0, 100, 100}}), {}));
  Frame huge;
  huge.placement = AtLimit, huge.shift = 16, huge.corner = 1;
  put(dir, "farthest-n-plus-8-limit", items(segs({{42, 79, -27, -52}, {-84, -54, 172, 130}, {56, -100, -24, 52},
                                                  {100, -61, -71, 73}, {18, -9, -32, 65}, {-50, 152, 26, -84}}), huge));

  // tests/cpp/layouts.hpp: drawn random layouts of each style, as drawn and against the limit.
  const char* names[] = {"rectilinear", "octilinear", "any-angle"};
  for (int style = Rectilinear; style <= AnyAngle; ++style)
    for (std::uint64_t seed : {1, 2}) {
      const auto layout = testing::random_layout(seed, testing::Style(style));
      Frame f;
      if (seed == 2) f.placement = AtLimit, f.corner = style, f.polygon_sites = true;
      put(dir, std::string("layout-") + names[style] + "-" + std::to_string(seed) + (seed == 2 ? "-limit" : ""),
          polygons(style, layout, f));
    }

  // The smallest cases of the known faults (known.hpp); tests/fuzz/corpus/finding-* are the
  // fuzzer's own findings, kept as found.
  put(dir, "known-far-boxes", polygons(Rectilinear, {testing::box(21562499, 21562499, 21562599, 21562539),
                                                     testing::box(21562649, 21562499, 21562699, 21562799)}, {}));
  put(dir, "known-slanted-segment", items(segs({{36866, 49921, 2, 51197}}), {}));
  Frame wide;
  wide.span = 3;
  put(dir, "known-slanted-parallelogram", polygons(AnyAngle, {{{{0, 0}, {35072, 2}, {35072, 1002}, {0, 1000}}, {}}}, wide));
  Frame untied = wide;
  untied.options = 8;  // no axis tie-break
  put(dir, "known-untied", polygons(Rectilinear, {{{{50544, 21177}, {50674, 21177}, {50674, 21918}, {36595, 21918},
                                                    {36595, 51870}, {47242, 51870}, {47242, 20098}, {50544, 20098}}, {}},
                                                  testing::box(0, 0, 21489, 10621)}, untied));
  return 0;
}
