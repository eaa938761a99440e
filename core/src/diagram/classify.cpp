#include "linf/diagram/classify.hpp"

namespace linf {

namespace {
double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

bool is_endpoint(const Site& seg, const Site& pt) {
  return !seg.is_point() && pt.is_point() && (pt.a == seg.a || pt.a == seg.b);
}
}  // namespace

bool inside_near(const Sites& s, std::int32_t id, const Vec2& p) {
  const Site& t = s.sites[id];
  if (!t.is_point())
    return cross(double(t.b.x - t.a.x), double(t.b.y - t.a.y), p.x - double(t.a.x), p.y - double(t.a.y)) > 0;
  // A ring vertex's neighbours are the far ends of its incoming and outgoing edges.
  const Point& v = t.a;
  const Point& prev = s.sites[t.end0].a;
  const Point& next = s.sites[t.end1].b;
  const double ox = double(next.x - v.x), oy = double(next.y - v.y);  // outgoing edge
  const double ix = double(prev.x - v.x), iy = double(prev.y - v.y);  // incoming edge, reversed
  const double ux = p.x - double(v.x), uy = p.y - double(v.y);
  const bool convex = cross(double(v.x - prev.x), double(v.y - prev.y), ox, oy) > 0;
  const bool left_of_out = cross(ox, oy, ux, uy) > 0;
  const bool right_of_in = cross(ux, uy, ix, iy) > 0;
  return convex ? (left_of_out && right_of_in) : (left_of_out || right_of_in);
}

PieceKind classify(const Sites& s, const Piece& piece) {
  const Site& a = s.sites[piece.a];
  const Site& b = s.sites[piece.b];
  if (is_endpoint(a, b) || is_endpoint(b, a)) return PieceKind::Adjacent;
  if (a.shape != b.shape || a.ring < 0 || b.ring < 0) return PieceKind::External;
  const Vec2 m{0.5 * (piece.p.x + piece.q.x), 0.5 * (piece.p.y + piece.q.y)};
  // Prefer a segment owner: its side test needs no wedge.
  const std::int32_t owner = a.is_point() ? piece.b : piece.a;
  return inside_near(s, owner, m) ? PieceKind::Internal : PieceKind::Notch;
}

const char* kind_name(PieceKind k) {
  switch (k) {
    case PieceKind::Internal: return "internal";
    case PieceKind::External: return "external";
    case PieceKind::Notch: return "notch";
    case PieceKind::Adjacent: return "adjacent";
  }
  return "?";
}

}  // namespace linf
