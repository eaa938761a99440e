// The farthest-site Voronoi diagram in L-inf: brute force, the thesis's structure theorems and
// their tight examples, the root against independent computations.
#include <gtest/gtest.h>

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "linf/farthest/farthest.hpp"

using namespace linf;

namespace {

std::vector<std::vector<Point>> sites_of(const std::vector<Segment>& S) {
  std::vector<std::vector<Point>> out;
  for (const Segment& s : S) out.push_back({s.a, s.b});
  return out;
}

bool contains_all(const std::vector<std::int32_t>& big, const std::vector<std::int32_t>& small) {
  return std::all_of(small.begin(), small.end(),
                     [&](std::int32_t x) { return std::find(big.begin(), big.end(), x) != big.end(); });
}

double cross(const Vec2& o, const Vec2& a, const Vec2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  return cross(a, b, c) * cross(a, b, d) <= 0 && cross(c, d, a) * cross(c, d, b) <= 0;
}

// Every vertex at its weight from its owners and no site farther; points sampled on every edge
// and ray have both faces' owners among the farthest; pairs of points with different unique
// farthest sites are separated by some edge. Returns the number of failures.
int check(const std::vector<Segment>& S, std::mt19937_64& rng) {
  const auto sites = sites_of(S);
  const FarthestDiagram d = farthest_voronoi(S);
  int bad = 0;
  std::vector<std::int32_t> own;
  for (const FarthestVertex& v : d.vertices) {
    const double w = farthest_distance(sites, v.at, &own, 1e-9);
    if (std::fabs(w - v.weight) > 1e-7 * (1 + w)) ++bad;
    for (std::int32_t f : v.faces) bad += !contains_all(own, d.faces[f].owners);
  }
  for (const FarthestEdge& e : d.edges) {
    const Vec2 p = d.vertices[e.from].at;
    std::vector<std::pair<Vec2, double>> samples;
    if (e.to >= 0) {
      const Vec2 q = d.vertices[e.to].at;
      for (double t : {0.25, 0.5, 0.75})
        samples.push_back({{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)},
                           d.vertices[e.from].weight + t * (d.vertices[e.to].weight - d.vertices[e.from].weight)});
    } else {
      for (double t : {1.0, 10.0, 1000.0}) samples.push_back({{p.x + t * e.direction.x, p.y + t * e.direction.y}, -1});
    }
    for (auto& [x, w] : samples) {
      const double f = farthest_distance(sites, x, &own, 1e-9);
      if (w >= 0 && std::fabs(f - w) > 1e-7 * (1 + f)) ++bad;
      bad += !contains_all(own, d.faces[e.left].owners) || !contains_all(own, d.faces[e.right].owners);
    }
  }
  // Completeness: some edge separates points whose farthest sites differ.
  std::uniform_real_distribution<double> U(-300, 300), V(-20, 20);
  for (int k = 0; k < 200; ++k) {
    const Vec2 a{U(rng), U(rng)}, b{a.x + V(rng), a.y + V(rng)};
    std::vector<std::int32_t> oa, ob;
    farthest_distance(sites, a, &oa, 1e-9);
    farthest_distance(sites, b, &ob, 1e-9);
    if (oa.size() != 1 || ob.size() != 1 || oa == ob) continue;
    bool crossed = false;
    for (const FarthestEdge& e : d.edges) {
      const Vec2 p = d.vertices[e.from].at;
      const Vec2 q = e.to >= 0 ? d.vertices[e.to].at : Vec2{p.x + 1e6 * e.direction.x, p.y + 1e6 * e.direction.y};
      if (segments_meet(a, b, p, q)) crossed = true;
    }
    bad += !crossed;
  }
  return bad;
}

std::vector<int> faces_per_site(const FarthestDiagram& d, std::size_t n) {
  std::vector<int> per(n, 0);
  for (const FarthestFace& f : d.faces)
    for (std::int32_t o : f.owners) ++per[o];
  return per;
}

// The root's half-side as a linear program (CGAL's exact solver): minimise r such that some
// point t_i of every segment lies within r of the centre in x and in y.
double lp_half_side(const std::vector<Segment>& S) {
  CGAL::Quadratic_program<double> lp(CGAL::SMALLER, false, 0, false, 0);
  int row = 0;
  for (std::size_t i = 0; i < S.size(); ++i) {
    const int t = 3 + int(i);
    const double ax = double(S[i].a.x), ay = double(S[i].a.y);
    const double dx = double(S[i].b.x - S[i].a.x), dy = double(S[i].b.y - S[i].a.y);
    for (int sgn : {1, -1}) {  // |c - (a + t d)| <= r, per coordinate
      lp.set_a(0, row, -sgn), lp.set_a(2, row, -1), lp.set_a(t, row, sgn * dx), lp.set_b(row, -sgn * ax), ++row;
      lp.set_a(1, row, -sgn), lp.set_a(2, row, -1), lp.set_a(t, row, sgn * dy), lp.set_b(row, -sgn * ay), ++row;
    }
    lp.set_l(t, true, 0), lp.set_u(t, true, 1);
  }
  lp.set_l(2, true, 0);
  lp.set_c(2, 1);
  const auto s = CGAL::solve_linear_program(lp, CGAL::Gmpzf());
  return CGAL::to_double(s.objective_value());
}

}  // namespace

TEST(Farthest, AgreesWithBruteForce) {
  std::mt19937_64 rng(11);
  auto u = [&](int lo, int hi) { return std::int64_t(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 600; ++round) {
    const int n = int(u(1, 10)), style = round % 4;
    std::vector<Segment> S;
    for (int i = 0; i < n; ++i) {
      Point a{u(0, 100), u(0, 100)}, b{u(0, 100), u(0, 100)};
      if (style == 1) b = a;                          // points
      if (style == 2) (u(0, 1) ? b.x : b.y) = u(0, 0) + (u(0, 1) ? a.x : a.y), b = (u(0, 1) ? Point{a.x, b.y} : Point{b.x, a.y});  // axis-parallel
      if (style == 3) b = {a.x + u(-30, 30), a.y + (u(0, 1) ? 1 : -1) * (b.x - a.x)};  // 45 degrees and others
      S.push_back({a, b});
    }
    ASSERT_EQ(check(S, rng), 0) << "round " << round;
  }
}

TEST(Farthest, StructureTheorems) {
  std::mt19937_64 rng(5);
  auto u = [&](int lo, int hi) { return std::int64_t(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 1500; ++round) {
    const int n = int(u(1, 12));
    std::vector<Segment> S;
    for (int i = 0; i < n; ++i) S.push_back({{u(-100, 100), u(-100, 100)}, {u(-100, 100), u(-100, 100)}});
    const FarthestDiagram d = farthest_voronoi(S);
    ASSERT_LE(int(d.faces.size()), n + 8);  // Theorem 2
    for (int c : faces_per_site(d, S.size())) ASSERT_LE(c, 5);  // Corollary 2
    // Non-crossing: keep the segments that cross none kept before.
    std::vector<Segment> T;
    for (const Segment& s : S) {
      bool ok = true;
      for (const Segment& t : T)
        ok &= !segments_meet({double(s.a.x), double(s.a.y)}, {double(s.b.x), double(s.b.y)},
                             {double(t.a.x), double(t.a.y)}, {double(t.b.x), double(t.b.y)});
      if (ok) T.push_back(s);
    }
    ASSERT_LE(farthest_voronoi(T).faces.size(), 8u);  // Theorem 2, non-crossing
  }
}

TEST(Farthest, TightExamples) {
  // Figure 3.10: one segment (the second) whose region has five faces.
  const std::vector<Segment> five{{{90, -60}, {-58, 24}}, {{-40, -27}, {80, 24}}, {{84, 35}, {-80, -64}}};
  const auto per = faces_per_site(farthest_voronoi(five), five.size());
  EXPECT_EQ(*std::max_element(per.begin(), per.end()), 5);
  // Figure 3.11: six segments, n + 8 = 14 faces.
  const std::vector<Segment> six{{{42, 79}, {-27, -52}},  {{-84, -54}, {172, 130}}, {{56, -100}, {-24, 52}},
                                 {{100, -61}, {-71, 73}}, {{18, -9}, {-32, 65}},    {{-50, 152}, {26, -84}}};
  EXPECT_EQ(farthest_voronoi(six).faces.size(), 14u);
  std::mt19937_64 rng(1);
  EXPECT_EQ(check(five, rng), 0);
  EXPECT_EQ(check(six, rng), 0);
}

TEST(Farthest, OnePointAndOneSegment) {
  const FarthestDiagram p = farthest_voronoi(std::vector<Segment>{{{5, 7}, {5, 7}}});
  ASSERT_EQ(p.faces.size(), 1u);  // every piece belongs to the one site: one face
  EXPECT_DOUBLE_EQ(p.root.half_side, 0);
  EXPECT_DOUBLE_EQ(p.root.p.x, 5);
  EXPECT_DOUBLE_EQ(p.root.p.y, 7);
  const FarthestDiagram s = farthest_voronoi(std::vector<Segment>{{{0, 0}, {40, 10}}});
  EXPECT_LE(s.faces.size(), 5u);
  EXPECT_DOUBLE_EQ(s.root.half_side, 0);
}

TEST(Farthest, RootOfAxisParallelSegments) {
  std::mt19937_64 rng(3);
  auto u = [&](int lo, int hi) { return std::int64_t(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 500; ++round) {
    std::vector<Segment> S;
    double xlo = -1e9, xhi = 1e9, ylo = -1e9, yhi = 1e9;
    for (int i = 0, n = int(u(1, 8)); i < n; ++i) {
      const Point a{u(0, 200), u(0, 200)};
      const Point b = u(0, 1) ? Point{a.x + u(0, 80), a.y} : Point{a.x, a.y + u(0, 80)};
      S.push_back({a, b});
      xlo = std::max(xlo, double(a.x)), xhi = std::min(xhi, double(b.x));
      ylo = std::max(ylo, double(a.y)), yhi = std::min(yhi, double(b.y));
    }
    const double expect = std::max({0.0, (xlo - xhi) / 2, (ylo - yhi) / 2});
    ASSERT_NEAR(farthest_voronoi(S).root.half_side, expect, 1e-9) << "round " << round;
  }
}

TEST(Farthest, RootAgainstALinearProgram) {
  std::mt19937_64 rng(8);
  auto u = [&](int lo, int hi) { return std::int64_t(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 200; ++round) {
    std::vector<Segment> S;
    for (int i = 0, n = int(u(1, 9)); i < n; ++i) S.push_back({{u(0, 100), u(0, 100)}, {u(0, 100), u(0, 100)}});
    const FarthestDiagram d = farthest_voronoi(S);
    ASSERT_NEAR(d.root.half_side, lp_half_side(S), 1e-7) << "round " << round;
    // The root's square touches every segment.
    const auto sites = sites_of(S);
    for (const Vec2& c : {d.root.p, d.root.q})
      ASSERT_LE(farthest_distance(sites, c), d.root.half_side + 1e-7);
  }
}

TEST(Farthest, L1ByRotation) {
  // L1 distance from a point to a segment, by its breakpoints (the axis crossings).
  auto l1 = [](const Vec2& p, const Segment& s) {
    const double ax = double(s.a.x), ay = double(s.a.y), dx = double(s.b.x - s.a.x), dy = double(s.b.y - s.a.y);
    auto f = [&](double t) { t = std::clamp(t, 0.0, 1.0); return std::fabs(p.x - ax - t * dx) + std::fabs(p.y - ay - t * dy); };
    double m = std::min(f(0), f(1));
    if (dx != 0) m = std::min(m, f((p.x - ax) / dx));
    if (dy != 0) m = std::min(m, f((p.y - ay) / dy));
    return m;
  };
  std::mt19937_64 rng(4);
  auto u = [&](int lo, int hi) { return std::int64_t(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  for (int round = 0; round < 300; ++round) {
    std::vector<Segment> S;
    for (int i = 0, n = int(u(1, 8)); i < n; ++i) S.push_back({{u(0, 100), u(0, 100)}, {u(0, 100), u(0, 100)}});
    const FarthestDiagram d = farthest_voronoi_l1(S);
    for (const FarthestVertex& v : d.vertices) {
      double far = 0;
      for (const Segment& s : S) far = std::max(far, l1(v.at, s));
      ASSERT_NEAR(far, v.weight, 1e-7 * (1 + far)) << "round " << round;
    }
  }
}

TEST(Farthest, DegenerateAndNonStandardPositions) {
  std::mt19937_64 rng(2);
  // Figure 3.8(c): l_n = l_s and l_e = l_w, the hull a point: a plus sign; its centre touches both.
  const std::vector<Segment> plus{{{0, 50}, {100, 50}}, {{50, 0}, {50, 100}}};
  const FarthestDiagram p = farthest_voronoi(plus);
  EXPECT_DOUBLE_EQ(p.root.half_side, 0);
  EXPECT_DOUBLE_EQ(p.root.p.x, 50);
  EXPECT_DOUBLE_EQ(p.root.p.y, 50);
  EXPECT_EQ(check(plus, rng), 0);
  // Figure 3.8(a): l_n = l_s only (the hull a segment): two horizontal segments on one line.
  const std::vector<Segment> line{{{0, 10}, {40, 10}}, {{100, 10}, {160, 10}}};
  const FarthestDiagram l = farthest_voronoi(line);
  EXPECT_DOUBLE_EQ(l.root.half_side, 30);
  EXPECT_EQ(check(line, rng), 0);
  // Figures 3.5(b) and 3.6: l_n below l_s, l_e right of l_w (axis-parallel, standing apart).
  const std::vector<Segment> apart{{{0, 0}, {30, 0}}, {{60, 80}, {60, 120}}, {{10, 200}, {10, 230}}};
  const FarthestDiagram a = farthest_voronoi(apart);
  EXPECT_DOUBLE_EQ(a.root.half_side, std::max({0.0, (60.0 - 10.0) / 2, (200.0 - 0.0) / 2}));
  EXPECT_EQ(check(apart, rng), 0);
  // Crossing segments all through one point, and a segment met by a repeated copy of itself.
  const std::vector<Segment> star{{{0, 0}, {100, 100}}, {{0, 100}, {100, 0}}, {{50, 0}, {50, 100}}, {{0, 0}, {100, 100}}};
  EXPECT_EQ(check(star, rng), 0);
  EXPECT_DOUBLE_EQ(farthest_voronoi(star).root.half_side, 0);
}

TEST(Farthest, VerticesRoundedNearTheLimit) {
  // The vertices are the roundings of their exact values: near 2^30 their weights are the
  // farthest distances there within a few ulps, not within CGAL's interval approximations
  // (this vertex's weight was 3.6e-3 off).
  const std::vector<Segment> S{{{-1073728373, -1073741771}, {-1073728748, -1073741771}},
                               {{-1073728408, -1073741811}, {-1073728408, -1073741803}},
                               {{-1073726471, -1073699839}, {-1073726469, -1073741823}},
                               {{-1073739775, -1073741823}, {-1073741823, -1073741823}}};
  const auto sites = sites_of(S);
  const FarthestDiagram d = farthest_voronoi(S);
  ASSERT_FALSE(d.vertices.empty());
  for (const FarthestVertex& v : d.vertices) {
    const double f = farthest_distance(sites, v.at);
    EXPECT_NEAR(f, v.weight, 1e-9 * (1 + f) + 1e-15 * 1073741824.0) << "at " << v.at.x << ", " << v.at.y;
  }
}
