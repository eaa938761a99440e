// The farthest-site Voronoi diagram in L-inf (thesis 3.1), and the smallest axis-parallel
// square that touches every site.
//
//   in:  sites, each a convex polygon given by its vertices in integer coordinates: a point
//        (1 vertex), a segment (2), or a convex polygon (3+, any order: its convex hull is
//        used). Segments may cross.
//   out: FarthestDiagram: faces (owner sites, unbounded direction), vertices (with weight =
//        the farthest distance there), edges (bounded, or rays of slope 0, inf or +-1), the
//        farthest hull as the circular list of its planes, and the root: the locus of minimum
//        weight (a point or a segment) with its half-side.
//
// Construction: the farthest distance F(x) = max over sites of d(x, s) is the upper envelope of
// affine pieces: for each site, (n.x - h_s(n)) / (|n_x| + |n_y|) over the normals n of the
// site (+) unit square (the four axis normals and the site's own edge normals). Per normal only
// the highest piece matters (the four axis ones are the thesis's bounding lines l_e, l_n, l_w,
// l_s). The envelope is the upper convex hull of the pieces' dual points (a, b, c), computed
// exactly (CGAL, exact predicates and constructions): hull vertices are the faces, upper
// facets the diagram's vertices, and hull edges its edges — a ray where an upper facet meets a
// vertical or lower one. Pieces tied on the same normal and offset belong to all their sites
// (the thesis's convention for a bounding line induced by several segments).
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

struct FarthestFace {
  std::vector<std::int32_t> owners;  // site indices (several when they tie, e.g. on l_e)
  Vec2 direction;                    // the direction in which the face is unbounded
  std::int32_t pieces = 1;           // envelope pieces merged into this face
};

struct FarthestVertex {
  Vec2 at;
  double weight = 0;                 // farthest L-inf distance = half-side of the square there
  std::vector<std::int32_t> faces;   // faces meeting here
};

struct FarthestEdge {
  std::int32_t left = -1, right = -1;  // the two faces
  std::int32_t from = -1, to = -1;     // vertices; to = -1 for a ray
  Vec2 direction;                      // a ray's direction (unit length)
};

struct FarthestRoot {
  Vec2 p, q;         // p == q for a point
  double half_side = 0;
};

struct FarthestDiagram {
  std::vector<FarthestFace> faces;
  std::vector<FarthestVertex> vertices;
  std::vector<FarthestEdge> edges;
  FarthestRoot root;
  std::int32_t hull_pieces = 0;  // envelope pieces (dual hull vertices) before merging faces
};

FarthestDiagram farthest_voronoi(const std::vector<std::vector<Point>>& sites);
FarthestDiagram farthest_voronoi(const std::vector<Segment>& segments);

// The same in L1, by the 45-degree map (x, y) -> (x + y, x - y) under which L1 becomes L-inf.
FarthestDiagram farthest_voronoi_l1(const std::vector<Segment>& segments);
// The same for sites given as vertex lists (a point or a segment each); throws
// std::invalid_argument for a polygon.
FarthestDiagram farthest_voronoi_l1(const std::vector<std::vector<Point>>& sites);

// The farthest L-inf distance from p to the sites, and which sites attain it (brute force).
double farthest_distance(const std::vector<std::vector<Point>>& sites, const Vec2& p,
                         std::vector<std::int32_t>* owners = nullptr, double tol = 1e-9);

}  // namespace linf
