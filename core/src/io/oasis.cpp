#include "linf/io/oasis.hpp"

#include <climits>

#include <boost/polygon/polygon.hpp>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace linf {

// OASIS (SEMI P39) records: a record id, then fields as variable-length integers (seven bits a
// byte, low groups first, the top bit set on all but the last) and strings (a length, then the
// bytes). Every geometry record here gives all of its fields, so no modal state is relied on
// but the position: coordinates are relative to the previous shape's (XYRELATIVE; texts and
// geometry each their own). After START the records go out in CBLOCKs, deflated a megabyte at
// a time, as KLayout writes them: a quarter of the size.
struct OasisWriter::Stream {
  std::unique_ptr<FILE, int (*)(FILE*)> f;
  std::string path, buf;   // buf: records not yet deflated
  std::string packed;      // deflate's output
  std::string cell;        // the CELL record comes after the names (names are not allowed in a cell)
  bool in_cell = false;
  std::int64_t gx = 0, gy = 0, tx = 0, ty = 0;  // the modal positions of geometry and of texts

  explicit Stream(const std::string& p) : f(std::fopen(p.c_str(), "wb"), &std::fclose), path(p) {
    if (!f) throw std::runtime_error("cannot write " + p);
    buf.reserve(1 << 20);
  }
  void byte(int b) { buf.push_back(char(b)); }
  void u(std::uint64_t v) {
    while (v >= 0x80) byte(int(v & 0x7f) | 0x80), v >>= 7;
    byte(int(v));
  }
  void s(std::int64_t v) { u(v < 0 ? (std::uint64_t(-v) << 1) | 1 : std::uint64_t(v) << 1); }
  void str(const std::string& t) {
    u(t.size());
    buf.append(t);
  }
  // A displacement: form 2 of a g-delta (|dx| with its sign and a flag in the low bits, then dy).
  void delta(std::int64_t dx, std::int64_t dy) {
    u((std::uint64_t(dx < 0 ? -dx : dx) << 2) | (dx < 0 ? 2 : 0) | 1);
    s(dy);
  }
  // KLayout reads a position or a displacement into 32 bits. Drawings reach +-(2^31 - 1)
  // (gds.hpp, cut_to_drawable), so a shape can lie further than that from the previous one: it
  // is placed absolutely (XYABSOLUTE before its record, XYRELATIVE again after it).
  static bool fits(std::int64_t d) { return d >= -std::int64_t(INT32_MAX) && d <= std::int64_t(INT32_MAX); }
  bool absolute = false;
  void place(std::int64_t x, std::int64_t y) {
    if (fits(x - gx) && fits(y - gy)) return;
    byte(15);  // XYABSOLUTE
    absolute = true;
  }
  void geometry_at(std::int64_t x, std::int64_t y) {
    if (absolute) {
      s(x), s(y);
    } else {
      s(x - gx), s(y - gy);
    }
    gx = x, gy = y;
  }
  void placed() {
    if (!absolute) return;
    byte(16);  // XYRELATIVE
    absolute = false;
  }
  void text_at(std::int64_t x, std::int64_t y) { s(x - tx), s(y - ty), tx = x, ty = y; }
  void open_cell() {
    if (in_cell) return;
    byte(14);  // CELL, by name
    str(cell);
    byte(16);  // XYRELATIVE
    in_cell = true;
    gx = gy = tx = ty = 0;
  }
  void write(const std::string& bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), f.get()) != bytes.size())
      throw std::runtime_error("error writing " + path);
  }
  // The pending records as one CBLOCK: comp-type 0 (raw DEFLATE), the sizes, the bytes.
  void pack() {
    if (buf.empty()) return;
    z_stream z{};
    if (deflateInit2(&z, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::runtime_error("zlib");
    packed.resize(deflateBound(&z, uLong(buf.size())));
    z.next_in = reinterpret_cast<Bytef*>(&buf[0]);
    z.avail_in = uInt(buf.size());
    z.next_out = reinterpret_cast<Bytef*>(&packed[0]);
    z.avail_out = uInt(packed.size());
    const int rc = deflate(&z, Z_FINISH);
    deflateEnd(&z);
    if (rc != Z_STREAM_END) throw std::runtime_error("zlib: cannot deflate");
    packed.resize(z.total_out);
    const std::size_t plain = buf.size();
    buf.clear();
    byte(34), u(0), u(plain), u(packed.size());  // CBLOCK
    write(buf);
    write(packed);
    buf.clear();
  }
  void flush_if_full() {
    if (buf.size() > (1 << 20)) pack();
  }
};

namespace {

// Names are n-strings: printable characters without the space; others become '*', as KLayout
// writes them.
std::string n_string(std::string t) {
  for (char& c : t)
    if (c < 0x21 || c > 0x7e) c = '*';
  return t;
}

}  // namespace

OasisWriter::OasisWriter(const std::string& path, double dbu, const std::string& cell)
    : s_(std::make_unique<Stream>(path)) {
  s_->buf.append("%SEMI-OASIS\r\n");
  s_->byte(1);  // START
  s_->str("1.0");
  const double steps = 1.0 / dbu;  // grid steps per micrometre
  if (std::fabs(steps - std::round(steps)) < 1e-9 * steps) {
    s_->u(0), s_->u(std::uint64_t(std::llround(steps)));  // real, type 0: a positive whole number
  } else {
    s_->u(7);  // real, type 7: IEEE double, little endian
    std::uint64_t bits;
    std::memcpy(&bits, &steps, sizeof bits);
    for (int i = 0; i < 8; ++i) s_->byte(int((bits >> (8 * i)) & 0xff));
  }
  s_->u(0);                                 // offset-flag: the table offsets follow here
  for (int i = 0; i < 12; ++i) s_->u(0);    // six tables, none
  s_->write(s_->buf);                       // the magic and START stay outside CBLOCKs
  s_->buf.clear();
  s_->cell = n_string(cell);
}

OasisWriter::~OasisWriter() = default;

void OasisWriter::layer_name(const std::string& name, int layer, int datatype) {
  if (s_->in_cell) throw std::logic_error("OASIS layer names come before the geometry");
  for (int record : {11, 12}) {  // LAYERNAME for geometry, then for texts
    s_->byte(record);
    s_->str(n_string(name));
    s_->u(3), s_->u(std::uint64_t(layer));     // interval: exactly this layer
    s_->u(3), s_->u(std::uint64_t(datatype));  // and this datatype
  }
}

void OasisWriter::polygon(int layer, int datatype, const Ring& r) {
  if (r.size() < 3) return;
  s_->open_cell();
  s_->place(r[0].x, r[0].y);
  s_->byte(21);    // POLYGON
  s_->byte(0x3b);  // info: point-list, x, y, datatype, layer
  s_->u(std::uint64_t(layer)), s_->u(std::uint64_t(datatype));
  s_->u(4), s_->u(r.size() - 1);  // point-list type 4 (g-deltas); the closing edge is implied
  for (std::size_t i = 1; i < r.size(); ++i) s_->delta(r[i].x - r[i - 1].x, r[i].y - r[i - 1].y);
  s_->geometry_at(r[0].x, r[0].y);
  s_->placed();
  s_->flush_if_full();
}

void OasisWriter::path(int layer, int datatype, std::int64_t x1, std::int64_t y1, std::int64_t x2, std::int64_t y2) {
  s_->open_cell();
  s_->place(x1, y1);
  s_->byte(22);    // PATH
  s_->byte(0xfb);  // info: extension scheme, half-width, point-list, x, y, datatype, layer
  s_->u(std::uint64_t(layer)), s_->u(std::uint64_t(datatype));
  s_->u(0);             // half-width
  s_->u(5);             // extension scheme: flush at both ends
  const std::int64_t dx = x2 - x1, dy = y2 - y1;
  if (Stream::fits(dx) && Stream::fits(dy)) {
    s_->u(4), s_->u(1);  // point-list type 4, one g-delta
    s_->delta(dx, dy);
  } else {
    // Longer than KLayout's 32-bit displacement (a ray across +-(2^31 - 1)): two halves,
    // through a middle point on the grid.
    s_->u(4), s_->u(2);
    s_->delta(dx / 2, dy / 2);
    s_->delta(dx - dx / 2, dy - dy / 2);
  }
  s_->geometry_at(x1, y1);
  s_->placed();
  s_->flush_if_full();
}

void OasisWriter::text(int layer, int datatype, std::int64_t x, std::int64_t y, const std::string& t) {
  s_->open_cell();
  s_->byte(19);    // TEXT
  s_->byte(0x5b);  // info: explicit string, x, y, texttype, textlayer
  s_->str(t);
  s_->u(std::uint64_t(layer)), s_->u(std::uint64_t(datatype));
  s_->text_at(x, y);
  s_->flush_if_full();
}

void OasisWriter::cell(const std::string& name) {
  s_->cell = n_string(name);
  s_->in_cell = false;
}

void OasisWriter::close() {
  s_->open_cell();  // an empty cell is still the layout's top cell
  s_->pack();
  // END, outside any CBLOCK: a padding string so that the record is 256 bytes long, then no
  // validation.
  s_->byte(2);
  s_->u(252);
  s_->buf.append(252, '\0');
  s_->u(0);
  if (s_->buf.size() != 256) throw std::logic_error("OASIS END record is not 256 bytes");
  s_->write(s_->buf);
  s_->buf.clear();
  if (std::fflush(s_->f.get()) != 0) throw std::runtime_error("error writing " + s_->path);
}

namespace {

namespace bp = boost::polygon;

// An outline with its holes as one ring: each hole joined to the outline by a cut line, as
// Boost.Polygon gives a polygon set to a type without holes.
std::vector<Ring> without_holes(const Polygon& p) {
  if (p.holes.empty()) return {p.outer};
  using Pt = bp::point_data<std::int64_t>;
  auto pts = [](const Ring& r) {
    std::vector<Pt> v;
    v.reserve(r.size());
    for (const Point& q : r) v.emplace_back(q.x, q.y);
    return v;
  };
  bp::polygon_with_holes_data<std::int64_t> ph;
  const std::vector<Pt> outer = pts(p.outer);
  ph.set(outer.begin(), outer.end());
  std::vector<bp::polygon_data<std::int64_t>> holes;
  for (const Ring& h : p.holes) {
    const std::vector<Pt> v = pts(h);
    holes.emplace_back(v.begin(), v.end());
  }
  ph.set_holes(holes.begin(), holes.end());
  bp::polygon_set_data<std::int64_t> set;
  set.insert(ph);
  std::vector<bp::polygon_data<std::int64_t>> out;
  set.get(out);
  std::vector<Ring> rings;
  for (const auto& q : out) {
    Ring r;
    for (const Pt& v : q) r.push_back({v.x(), v.y()});
    if (r.size() > 1 && r.front() == r.back()) r.pop_back();
    rings.push_back(std::move(r));
  }
  return rings;
}

// The core's own GDSII drawings: records of a 16-bit big-endian length, a type and a data type.
class GdsReader {
 public:
  explicit GdsReader(const std::string& path) : f_(std::fopen(path.c_str(), "rb"), &std::fclose), path_(path) {
    if (!f_) throw std::runtime_error("cannot read " + path);
  }
  // The next record's type, its data in `data`; false at the end of the file.
  bool next(int& type, std::string& data) {
    unsigned char h[4];
    if (std::fread(h, 1, 4, f_.get()) != 4) return false;
    const std::size_t n = (std::size_t(h[0]) << 8 | h[1]);
    if (n < 4) throw std::runtime_error("corrupt drawing " + path_);
    type = h[2];
    data.resize(n - 4);
    if (n > 4 && std::fread(&data[0], 1, n - 4, f_.get()) != n - 4) throw std::runtime_error("truncated drawing " + path_);
    return true;
  }
  static std::int32_t i32(const std::string& d, std::size_t at) {
    const auto* b = reinterpret_cast<const unsigned char*>(d.data()) + at;
    return std::int32_t(std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3]);
  }
  static int i16(const std::string& d) {
    const auto* b = reinterpret_cast<const unsigned char*>(d.data());
    return int(std::int16_t(std::uint16_t(b[0]) << 8 | b[1]));
  }

 private:
  std::unique_ptr<FILE, int (*)(FILE*)> f_;
  std::string path_;
};

}  // namespace

std::vector<Ring> outlines(const Polygon& p) { return without_holes(p); }

Ring box_ring(const std::array<std::int64_t, 4>& b) { return {{b[0], b[1]}, {b[2], b[1]}, {b[2], b[3]}, {b[0], b[3]}}; }

std::size_t oasis_from_drawing(const std::string& drawing, const FlatPolygons& input, int layer,
                               int datatype, const std::vector<LayerName>& names, double dbu,
                               const std::string& cell, const std::string& path,
                               const std::vector<LayerBoxes>& boxes) {
  OasisWriter w(path, dbu, cell);
  for (const LayerName& n : names) w.layer_name(n.name, n.layer, n.datatype);
  std::size_t shapes = 0;
  const PolygonIndex ix(input);
  for (std::size_t i = 0; i < ix.size(); ++i)
    for (const Ring& r : without_holes(ix.polygon(i))) w.polygon(layer, datatype, r), ++shapes;
  for (const LayerBoxes& lb : boxes)
    for (const auto& b : lb.boxes) w.polygon(lb.layer, lb.datatype, box_ring(b)), ++shapes;
  if (drawing.empty()) {
    w.close();
    return shapes;
  }
  GdsReader in(drawing);
  int type = 0, element = 0, l = 0, d = 0;
  std::string data, xy, text;
  while (in.next(type, data)) {
    switch (type) {
      case 0x09: case 0x0C: element = type, xy.clear(), text.clear(); break;  // PATH, TEXT
      case 0x0D: l = GdsReader::i16(data); break;                               // LAYER
      case 0x0E: case 0x16: d = GdsReader::i16(data); break;                    // DATATYPE, TEXTTYPE
      case 0x10: xy = data; break;                                              // XY
      case 0x19: text = data.substr(0, data.find('\0')); break;                 // STRING
      case 0x11:                                                                // ENDEL
        if (element == 0x09 && xy.size() == 16) {
          const std::int32_t x1 = GdsReader::i32(xy, 0), y1 = GdsReader::i32(xy, 4);
          const std::int32_t x2 = GdsReader::i32(xy, 8), y2 = GdsReader::i32(xy, 12);
          if (x1 != x2 || y1 != y2) w.path(l, d, x1, y1, x2, y2), ++shapes;  // KLayout drops a path of one point
        } else if (element == 0x0C && xy.size() == 8) {
          w.text(l, d, GdsReader::i32(xy, 0), GdsReader::i32(xy, 4), text);
          ++shapes;
        } else {
          throw std::runtime_error("unexpected element in drawing " + drawing);
        }
        element = 0;
        break;
      default: break;
    }
  }
  w.close();
  return shapes;
}

}  // namespace linf
