// The sites of the far field: which sites can own a point outside the inner box (builder.cpp's
// second pass), from what the first pass found on that box's border.
//
// A site t that owns an outside point p is an L-inf nearest site of p (the L1 tie-break only
// chooses among those). On the segment from p to t's L-inf nearest point t', t stays an L-inf
// nearest site (the triangle inequality, as in every norm), and that segment crosses the border
// (t' lies inside). So t is an L-inf nearest site, tied or not, at a border point q: it meets
// the square of radius f(q) about q, f being the L-inf distance to the nearest site. The owners
// of the border alone do not suffice: where sites tie in L-inf, the L1 tie-break can give one a
// region farther out whose every border point another site wins.
//
// Between two consecutive points where pieces end on the border, one site owns the border, so f
// is its distance there: convex, at most the larger of its ends. The squares over that stretch
// lie in the stretch's box grown by that value; every site meeting one of these boxes is kept.
// At a corner f is bounded from the nearest mark (f is 1-Lipschitz in L-inf).
#pragma once
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf::detail {

struct BorderMark {
  Vec2 v;    // a point of the inner box's border where a piece of the first pass ends
  double d;  // the L-inf distance to its owners there
};

// Ids of the sites (coordinates relative to origin, as inner and the marks) that meet a square
// about a border point of radius the L-inf distance there: sorted, without repeats; all of them
// when there is no mark.
std::vector<int> far_field_sites(const SiteList& sites, const Point& origin, const Box& inner,
                                 const std::vector<BorderMark>& marks);

}  // namespace linf::detail
