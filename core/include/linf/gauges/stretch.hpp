// Stretches: the diagram regrouped by what it separates.
//
//   in:  a Diagram (pieces with owner sites)
//   out: Stretches = maximal chains of pieces owned by the same two sites, as ordered paths
//        with the clearance at every path point; plus, at diagram vertices where three or
//        more sites meet, a point stretch for each meeting pair that has no chain of its own
//        (the centre of a square via, where the four corner bisectors meet, is the only place
//        its top and bottom edges are equally near).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "linf/util/paged.hpp"
#include "linf/geometry/piece.hpp"

namespace linf {

// A read-only run of values inside one of Stretches' shared arrays.
template <class T>
struct Span {
  const T* data = nullptr;
  std::size_t n = 0;
  const T* begin() const { return data; }
  const T* end() const { return data + n; }
  std::size_t size() const { return n; }
  const T& operator[](std::size_t i) const { return data[i]; }
  const T& front() const { return data[0]; }
  const T& back() const { return data[n - 1]; }
};

// One stretch, a view into the Stretches it came from (valid while they live).
struct Stretch {
  std::int32_t a = -1, b = -1;   // owner sites, a < b
  PieceKind kind = PieceKind::External;
  Span<Vec2> path;               // at least one point; consecutive points are piece ends
  Span<double> clearance;        // L-inf clearance to the owners at each path point
  double length = 0;             // Euclidean length of the path
};

// All stretches of a diagram in three flat arrays: a layer has millions, and a pair of heap
// vectors each would cost more than the stretches themselves. The arrays are Paged (mapped
// temporary files): on a full layer they are gigabytes that the kernel may write out and drop.
class Stretches {
 public:
  std::size_t size() const { return heads_.size(); }
  Stretch operator[](std::size_t i) const {
    const Head& h = heads_[i];
    return {h.a, h.b, h.kind, {points_.data() + h.first, h.count}, {clearance_.data() + h.first, h.count}, h.length};
  }

  // Building: reserve() room if known, open() a stretch, add() its points in order.
  void reserve(std::size_t stretches, std::size_t points) {
    heads_.reserve(stretches);
    points_.reserve(points);
    clearance_.reserve(points);
  }
  void open(std::int32_t a, std::int32_t b, PieceKind kind) {
    heads_.push_back({a, b, std::uint32_t(points_.size()), 0, 0, kind});
  }
  void add(const Vec2& p, double clearance) {
    points_.push_back(p);
    clearance_.push_back(clearance);
    ++heads_.back().count;
  }
  void lengthen(double d) { heads_.back().length += d; }
  bool empty_path() const { return heads_.back().count == 0; }

  // Keeps the stretches i with keep[i], in order, and gives the room of the rest back: on a full
  // layer half the measurable stretches make no gauge.
  void keep_only(const std::vector<bool>& keep);

 private:
  struct Head {
    std::int32_t a, b;
    std::uint32_t first, count;
    double length;
    PieceKind kind;
  };
  Paged<Head> heads_;
  Paged<Vec2> points_;
  Paged<double> clearance_;
};

// Which owner pairs (a < b, with the stretch's kind) get stretches.
using StretchFilter = std::function<bool(std::int32_t a, std::int32_t b, PieceKind kind)>;

// There is one way to build stretches, StretchStream below; a whole diagram is a stream of one
// part. Every stretch of the diagram, or only those between pairs `keep` accepts: the gauges
// need a small share of them, and the rest would be most of the stage's memory on a large layer.
Stretches stretches_of(const Diagram& d, const StretchFilter& keep = nullptr);

// The same, taking the diagram's pieces: they are consumed front to back and their memory given
// back as the stretches grow, so that a large layer never holds both whole. d.pieces is empty
// afterwards. Same stretches, same order.
Stretches take_stretches(Diagram& d, const StretchFilter& keep = nullptr);

// Stretches of a diagram that comes in parts (build_parts), for a layer too large to hold its
// pieces: the same stretches in the same order as stretches_of on the joined diagram. First
// every part as build_parts hands it over, with kinds: its vertices away from its frame have
// all their pieces there and give their point stretches at once; those on the frame wait.
// Then every owner pair's final pieces (joined over the parts, as join_pieces orders them),
// pairs ascending. finish() settles the waiting vertices and which point stretches' pairs
// have a chain elsewhere.
class StretchStream {
 public:
  StretchStream(const Sites& sites, StretchFilter keep, std::size_t expected_pieces = 0);
  ~StretchStream();
  void part(const std::vector<Piece>& part, const Box& frame);
  // part() in two steps: read() depends on the part alone (it only reads the stream's sites and
  // filter, which must be safe to call from several threads) and may run on any thread, several
  // parts at once; add() then takes the readings in the parts' order. part(p, f) is
  // add(*read(p, f)).
  struct Reading;
  std::shared_ptr<const Reading> read(const std::vector<Piece>& part, const Box& frame) const;
  void add(const Reading& reading);
  // read() where the part's owners are numbered locally (a tile task's sites: local site i is
  // the layer's site global[i], ascending, so the order of pairs is kept), as bytes with the
  // layer's ids; reading() makes them a Reading again (std::invalid_argument if malformed).
  std::string read_bytes(const std::vector<Piece>& part, const Box& frame, const std::vector<int>& global) const;
  static std::shared_ptr<const Reading> reading(const std::string& bytes);
  void pair(const Piece* pieces, std::size_t n);
  Stretches finish();

 private:
  void read_into(const std::vector<Piece>& part, const Box& frame, Reading& r) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Two sites are adjacent when they share a vertex (an edge and its endpoint, two edges of one
// corner, the two ends of one edge): the distance between them is not a width or a space.
bool adjacent(const Sites& s, std::int32_t a, std::int32_t b);

}  // namespace linf
