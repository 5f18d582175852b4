// Polygon properties, clipping and the contact geometry of two convex polygons
// (polygon-dem.md sections 2 and 3).
//
// Tolerances. Shapes near the origin are exact up to a few ulps, so analytic values are checked to
// 1e-12 relative (about 5000 ulps: room for sums over a few vertices and for sin/cos in rotated
// shapes). Shapes moved by +1e3 have their coordinates rounded to ulp(1e3)/2 = 5.7e-14 absolute,
// which perturbs a unit shape by ~1e-13 relative: still inside 1e-12, so no relaxation is needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "geometry/overlap.hpp"
#include "geometry/polygon.hpp"
#include "geometry/separation.hpp"
#include "mesh/random_lattice.hpp"

namespace {

using frac::geometry::ContactGeometry;
using frac::geometry::convex_overlap;
using frac::geometry::Polygon;
using frac::geometry::Vec2;
namespace geo = frac::geometry;
using Kind = ContactGeometry::Kind;

constexpr double kPi = std::numbers::pi;
const double kSqrt3 = std::sqrt(3.0);

Polygon rect(double x0, double y0, double w, double h) {
  return {Vec2(x0, y0), Vec2(x0 + w, y0), Vec2(x0 + w, y0 + h), Vec2(x0, y0 + h)};
}

// Regular n-gon of side s centred at c, first vertex at angle phase (counter-clockwise).
Polygon regular(int n, double s, const Vec2& c, double phase = 0.0) {
  const double radius = s / (2.0 * std::sin(kPi / n));
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = phase + 2.0 * kPi * k / n;
    p.emplace_back(c.x() + radius * std::cos(a), c.y() + radius * std::sin(a));
  }
  return p;
}

Vec2 rotate(const Vec2& v, double angle) {
  const double co = std::cos(angle), si = std::sin(angle);
  return Vec2(co * v.x() - si * v.y(), si * v.x() + co * v.y());
}

// Rotate about `pivot`, then translate by `shift`.
Polygon moved(const Polygon& p, double angle, const Vec2& pivot, const Vec2& shift) {
  Polygon out;
  for (const auto& v : p) out.push_back(pivot + rotate(v - pivot, angle) + shift);
  return out;
}

Polygon reversed(Polygon p) {
  std::reverse(p.begin(), p.end());
  return p;
}

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// Every field finite; the normal a unit vector (zero for `none`) pointing from c_i toward c_j.
void expect_well_formed(const ContactGeometry& r, const Vec2& ci, const Vec2& cj) {
  ASSERT_TRUE(std::isfinite(r.area));
  ASSERT_TRUE(finite(r.p1) && finite(r.p2) && finite(r.point) && finite(r.normal));
  EXPECT_GE(r.area, 0.0);
  if (r.kind == Kind::none) {
    EXPECT_EQ(r.area, 0.0);
    EXPECT_EQ(r.normal, Vec2(0, 0));
  } else {
    EXPECT_NEAR(r.normal.norm(), 1.0, 1e-15);
    EXPECT_GE(r.normal.dot(cj - ci), 0.0);
  }
}

ContactGeometry overlap(const Polygon& pi, const Polygon& pj, double g = 1.0) {
  return convex_overlap(pi, pj, geo::centroid(pi), geo::centroid(pj), g);
}

// {a, b} equals {p, q} in either order within tol.
void expect_same_pair(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q, double tol) {
  const bool direct = (a - p).norm() <= tol && (b - q).norm() <= tol;
  const bool swapped = (a - q).norm() <= tol && (b - p).norm() <= tol;
  EXPECT_TRUE(direct || swapped) << "got (" << a.transpose() << ") (" << b.transpose() << "), want (" << p.transpose()
                                 << ") (" << q.transpose() << ")";
}

double distance_to_boundary(const Vec2& x, const Polygon& p) {
  double best = INFINITY;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec2 a = p[k], d = p[(k + 1) % p.size()] - a;
    const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * d - x).norm());
  }
  return best;
}

// Proper crossings of the two boundaries by brute force over all edge pairs (generic position).
std::vector<Vec2> brute_force_crossings(const Polygon& p, const Polygon& q) {
  std::vector<Vec2> out;
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Vec2 p0 = p[a], dp = p[(a + 1) % p.size()] - p0;
    for (std::size_t b = 0; b < q.size(); ++b) {
      const Vec2 q0 = q[b], dq = q[(b + 1) % q.size()] - q0;
      const double den = geo::cross(dp, dq);
      if (den == 0.0) continue;
      const double t = geo::cross(q0 - p0, dq) / den, u = geo::cross(q0 - p0, dp) / den;
      if (t >= 0.0 && t < 1.0 && u >= 0.0 && u < 1.0) out.push_back(p0 + t * dp);
    }
  }
  return out;
}

// Random convex polygon: 3..10 points on an ellipse at sorted random angles, rotated, centred at c.
Polygon random_convex(frac::Rng& rng, const Vec2& c, double size) {
  const int n = 3 + static_cast<int>(rng.uniform() * 8.0);
  std::vector<double> angle;
  for (int k = 0; k < n; ++k) angle.push_back(rng.uniform(0.0, 2.0 * kPi));
  std::sort(angle.begin(), angle.end());
  const double ax = size * rng.uniform(0.5, 1.0), ay = size * rng.uniform(0.2, 1.0), tilt = rng.uniform(0.0, kPi);
  Polygon p;
  for (double a : angle) p.push_back(c + rotate(Vec2(ax * std::cos(a), ay * std::sin(a)), tilt));
  return p;
}

// ---------------------------------------------------------------------------------------------
// Polygon properties

struct Shape {
  const char* name;
  Polygon poly;
  double area;
  Vec2 centroid;
  double j;  // polar second moment about the centroid
};

std::vector<Shape> analytic_shapes() {
  // Triangle: J_c = A (a^2 + b^2 + c^2) / 36. Rectangle w x h: A (w^2 + h^2) / 12. Regular hexagon
  // of side s: A = 3 sqrt(3)/2 s^2, J = 5 sqrt(3)/8 s^4.
  const Polygon tri{Vec2(0, 0), Vec2(3, 0), Vec2(0, 4)};
  const Polygon equi = regular(3, 2.0, Vec2(0.5, -0.25), 0.1);
  const double s = 0.7;
  return {
      {"right triangle", tri, 6.0, Vec2(1.0, 4.0 / 3.0), 6.0 * (9.0 + 16.0 + 25.0) / 36.0},
      {"equilateral triangle", equi, kSqrt3, Vec2(0.5, -0.25), kSqrt3 * 12.0 / 36.0},
      {"unit square", rect(0, 0, 1, 1), 1.0, Vec2(0.5, 0.5), 1.0 / 6.0},
      {"rectangle", rect(-1, 2, 3, 0.5), 1.5, Vec2(0.5, 2.25), 1.5 * (9.0 + 0.25) / 12.0},
      {"regular hexagon", regular(6, s, Vec2(0.2, 0.3), 0.4), 1.5 * kSqrt3 * s * s, Vec2(0.2, 0.3),
       5.0 * kSqrt3 / 8.0 * std::pow(s, 4)},
  };
}

TEST(Polygon, AnalyticAreaCentroidSecondMoment) {
  for (const auto& sh : analytic_shapes()) {
    SCOPED_TRACE(sh.name);
    const double size = std::sqrt(sh.area);
    EXPECT_NEAR(geo::signed_area(sh.poly), sh.area, 1e-12 * sh.area);
    EXPECT_NEAR((geo::centroid(sh.poly) - sh.centroid).norm(), 0.0, 1e-12 * size);
    EXPECT_NEAR(geo::polar_second_moment(sh.poly), sh.j, 1e-12 * sh.j);
  }
}

TEST(Polygon, InvariantUnderFarTranslationAndRotation) {
  const std::vector<std::pair<double, Vec2>> moves = {
      {0.0, Vec2(1e3, 1e3)}, {0.7, Vec2(0, 0)}, {-2.1, Vec2(1e3, -1e3)}, {kPi / 3.0, Vec2(-1e3, 2e3)}};
  for (const auto& sh : analytic_shapes()) {
    for (const auto& [angle, shift] : moves) {
      SCOPED_TRACE(std::string(sh.name) + " angle " + std::to_string(angle) + " shift " + std::to_string(shift.x()));
      const Polygon p = moved(sh.poly, angle, sh.centroid, shift);
      const double size = std::sqrt(sh.area);
      EXPECT_NEAR(geo::signed_area(p), sh.area, 1e-12 * sh.area);
      // The centroid is compared to the shape's size, not to |c| ~ 1e3 (which would be lax).
      EXPECT_NEAR((geo::centroid(p) - (sh.centroid + shift)).norm(), 0.0, 1e-12 * size);
      EXPECT_NEAR(geo::polar_second_moment(p), sh.j, 1e-12 * sh.j);
    }
  }
}

TEST(Polygon, ClockwiseIsNegativeAndDegenerateIsZero) {
  const Polygon sq = rect(0, 0, 2, 1);
  EXPECT_DOUBLE_EQ(geo::signed_area(reversed(sq)), -2.0);
  EXPECT_DOUBLE_EQ(geo::polar_second_moment(reversed(sq)), -geo::polar_second_moment(sq));
  EXPECT_EQ(geo::signed_area(Polygon{Vec2(0, 0), Vec2(1, 1)}), 0.0);
  EXPECT_EQ(geo::polar_second_moment(Polygon{Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}), 0.0);
  // A degenerate polygon's centroid is the mean of its vertices.
  EXPECT_EQ(geo::centroid(Polygon{Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}), Vec2(1, 1));
}

TEST(Polygon, EqualAreaDiameter) {
  EXPECT_NEAR(geo::equal_area_diameter(kPi), 2.0, 1e-15);
  EXPECT_NEAR(geo::equal_area_diameter(kPi * 0.25 * 0.25), 0.5, 1e-15);
  EXPECT_EQ(geo::equal_area_diameter(0.0), 0.0);
  // A unit square: r = 2/sqrt(pi).
  EXPECT_NEAR(geo::equal_area_diameter(geo::signed_area(rect(0, 0, 1, 1))), 2.0 / std::sqrt(kPi), 1e-15);
}

TEST(Polygon, IsConvexCcwAcceptsConvexCounterClockwise) {
  EXPECT_TRUE(geo::is_convex_ccw(rect(0, 0, 1, 1)));
  EXPECT_TRUE(geo::is_convex_ccw(regular(6, 1.0, Vec2(1e3, 1e3), 0.3)));
  EXPECT_TRUE(geo::is_convex_ccw(regular(3, 1e-3, Vec2(0, 0))));
  // Collinear and repeated vertices are allowed.
  EXPECT_TRUE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 0), Vec2(1, 1), Vec2(1, 1), Vec2(0, 1)}));
  // A reflex turn within tolerance (1e-14 rad) counts as straight.
  EXPECT_TRUE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(0.5, -1e-14), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}));
}

TEST(Polygon, IsConvexCcwRejectsClockwiseReflexAndStar) {
  EXPECT_FALSE(geo::is_convex_ccw(reversed(rect(0, 0, 1, 1))));
  // Arrow head: reflex vertex at (0.5, 0.3).
  EXPECT_FALSE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(0.5, 0.3), Vec2(1, 0), Vec2(0.5, 1)}));
  EXPECT_FALSE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(0.5, 1e-3), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}));
  // Pentagram: only left turns and positive area, but it winds twice.
  const Polygon penta = regular(5, 1.0, Vec2(0, 0));
  const Polygon star{penta[0], penta[2], penta[4], penta[1], penta[3]};
  ASSERT_GT(geo::signed_area(star), 0.0);
  EXPECT_FALSE(geo::is_convex_ccw(star));
  // Too few vertices, zero area.
  EXPECT_FALSE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(1, 0)}));
  EXPECT_FALSE(geo::is_convex_ccw(Polygon{Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)}));
}

TEST(Polygon, ClipHalfPlane) {
  const Polygon sq = rect(0, 0, 1, 1);
  // Keep the left of the upward line x = 0.25.
  const Polygon left = geo::clip_half_plane(sq, Vec2(0.25, 0), Vec2(0.25, 1));
  EXPECT_NEAR(geo::signed_area(left), 0.25, 1e-15);
  // Vertices exactly on the line are not repeated: the right half of x = 1 is the edge only.
  EXPECT_EQ(geo::clip_half_plane(sq, Vec2(1, 1), Vec2(1, 0)).size(), 2u);
  // With a tolerance the half-plane is x <= 0.25 + 0.05: every vertex of the result lies inside it.
  const Polygon wide = geo::clip_half_plane(sq, Vec2(0.25, 0), Vec2(0.25, 1), 0.05);
  EXPECT_NEAR(geo::signed_area(wide), 0.30, 1e-15);
  for (const auto& v : wide) EXPECT_LE(v.x(), 0.30 + 1e-15);
  // The whole polygon inside: returned unchanged.
  EXPECT_EQ(geo::clip_half_plane(sq, Vec2(2, 0), Vec2(2, 1)), sq);
}

TEST(Polygon, ClipConvexBasicCases) {
  const Polygon a = rect(0, 0, 1, 1);
  EXPECT_NEAR(geo::signed_area(geo::clip_convex(a, rect(0.5, 0.25, 1, 1))), 0.375, 1e-15);
  EXPECT_TRUE(geo::clip_convex(a, rect(2, 0, 1, 1)).empty());                          // disjoint
  EXPECT_TRUE(geo::clip_convex(a, rect(1, 0, 1, 1)).empty());                          // shared edge
  EXPECT_NEAR(geo::signed_area(geo::clip_convex(a, rect(-1, -1, 3, 3))), 1.0, 1e-15);  // inside
  EXPECT_NEAR(geo::signed_area(geo::clip_convex(rect(-1, -1, 3, 3), a)), 1.0, 1e-15);  // contains
  // Triangle (0,0) (2,0) (0,2) against [0.5,1.5]x[0,1]: 0.5 (x < 1) + 0.375 (x > 1) = 0.875.
  const Polygon tri{Vec2(0, 0), Vec2(2, 0), Vec2(0, 2)};
  const Polygon cut = geo::clip_convex(tri, rect(0.5, 0, 1, 1), 1e-12);
  EXPECT_NEAR(geo::signed_area(cut), 0.875, 1e-15);
  EXPECT_TRUE(geo::is_convex_ccw(cut));
  // Hexagon against itself: itself.
  const Polygon hex = regular(6, 1.0, Vec2(0.3, 0.1), 0.2);
  EXPECT_NEAR(geo::signed_area(geo::clip_convex(hex, hex)), 1.5 * kSqrt3, 1e-14);
}

TEST(Polygon, Simplify) {
  const Polygon p{Vec2(0, 0), Vec2(1e-13, 0), Vec2(0.5, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0, 1e-13)};
  const Polygon s = geo::simplify(p, 1e-12);
  EXPECT_EQ(s.size(), 4u);
  EXPECT_NEAR(geo::signed_area(s), 1.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Contact geometry

TEST(Overlap, OffsetUnitSquares) {
  const Polygon pi = rect(0, 0, 1, 1), pj = rect(0.5, 0.25, 1, 1);
  geo::OverlapPolygon ov;
  const auto r = convex_overlap(pi, pj, Vec2(0.5, 0.5), Vec2(1.0, 0.75), 1.0, ov);
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(1.0, 0.75));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.375, 1e-12);
  EXPECT_EQ(r.crossings, 2);
  EXPECT_EQ(r.distinct_crossings, 2);
  // P_i's right edge crosses P_j's bottom at (1, 0.25); P_i's top crosses P_j's left at (0.5, 1).
  expect_same_pair(r.p1, r.p2, Vec2(1.0, 0.25), Vec2(0.5, 1.0), 1e-15);
  EXPECT_NEAR((r.point - Vec2(0.75, 0.625)).norm(), 0.0, 1e-15);
  // Perpendicular to (-0.5, 0.75), toward j: (3, 2)/sqrt(13).
  EXPECT_NEAR((r.normal - Vec2(3.0, 2.0) / std::sqrt(13.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(geo::signed_area(ov.vertices()), 0.375, 1e-15);
  EXPECT_TRUE(geo::is_convex_ccw(ov.vertices()));
}

TEST(Overlap, RotatedSquarePairFarFromOrigin) {
  const Vec2 shift(1e3, -1e3);
  for (double angle : {0.3, 1.0, -2.5, kPi / 4.0}) {
    SCOPED_TRACE(angle);
    const Vec2 pivot(0, 0);
    const Polygon pi = moved(rect(0, 0, 1, 1), angle, pivot, shift);
    const Polygon pj = moved(rect(0.5, 0.25, 1, 1), angle, pivot, shift);
    const auto r = overlap(pi, pj);
    expect_well_formed(r, geo::centroid(pi), geo::centroid(pj));
    EXPECT_EQ(r.kind, Kind::line);
    EXPECT_NEAR(r.area, 0.375, 1e-12 * 0.375);
    // Inputs carry ~1e-13 absolute rounding at 1e3: points to 1e-12.
    expect_same_pair(r.p1, r.p2, rotate(Vec2(1.0, 0.25), angle) + shift, rotate(Vec2(0.5, 1.0), angle) + shift, 1e-12);
    EXPECT_NEAR((r.normal - rotate(Vec2(3.0, 2.0) / std::sqrt(13.0), angle)).norm(), 0.0, 1e-12);
  }
}

TEST(Overlap, HexagonPair) {
  // Hexagons with vertices at 0, 60, ... degrees (flat top and bottom), side 1, j above i by d. The
  // width at height y is 2 - 2|y|/sqrt(3), so A_ov = 3 sqrt(3)/2 - 2 d + d^2/(2 sqrt(3)), and the
  // slanted sides cross at y = d/2, x = +-(1 - d/(2 sqrt(3))).
  for (double d : {0.1, 0.5, 1.2, 1.7}) {
    SCOPED_TRACE(d);
    const Polygon pi = regular(6, 1.0, Vec2(0, 0)), pj = regular(6, 1.0, Vec2(0, d));
    const auto r = convex_overlap(pi, pj, Vec2(0, 0), Vec2(0, d), 1.0);
    expect_well_formed(r, Vec2(0, 0), Vec2(0, d));
    EXPECT_EQ(r.kind, Kind::line);
    const double want = 1.5 * kSqrt3 - 2.0 * d + d * d / (2.0 * kSqrt3);
    EXPECT_NEAR(r.area, want, 1e-12 * want);
    const double x = 1.0 - d / (2.0 * kSqrt3);
    expect_same_pair(r.p1, r.p2, Vec2(x, d / 2), Vec2(-x, d / 2), 1e-14);
    EXPECT_NEAR((r.normal - Vec2(0, 1)).norm(), 0.0, 1e-14);
    EXPECT_NEAR((r.point - Vec2(0, d / 2)).norm(), 0.0, 1e-14);
  }
}

TEST(Overlap, SharedEdgeIsNoContact) {
  const auto r = overlap(rect(0, 0, 1, 1), rect(1, 0, 1, 1));
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(1.5, 0.5));
  EXPECT_EQ(r.kind, Kind::none);
  // Honeycomb neighbours built independently, rotated and moved: the common side matches only to
  // round-off, so the clipped sliver (if any) is ~1e-16 and below eps_A = 1e-12 g^2.
  for (double angle : {0.0, 0.37, 1.9}) {
    const Vec2 c1 = Vec2(12.3, -7.1), c2 = c1 + rotate(Vec2(0, kSqrt3), angle);
    const Polygon h1 = regular(6, 1.0, c1, angle), h2 = regular(6, 1.0, c2, angle);
    const auto rh = overlap(h1, h2);
    expect_well_formed(rh, c1, c2);
    EXPECT_EQ(rh.kind, Kind::none) << angle;
    EXPECT_EQ(overlap(h2, h1).kind, Kind::none) << angle;
  }
}

TEST(Overlap, TouchingVerticesIsNoContact) {
  // Corner to corner.
  auto r = overlap(rect(0, 0, 1, 1), rect(1, 1, 1, 1));
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(1.5, 1.5));
  EXPECT_EQ(r.kind, Kind::none);
  // A triangle's apex on a square's edge, from outside.
  const Polygon tri{Vec2(0.5, 1.0), Vec2(1.0, 2.0), Vec2(0.0, 2.0)};
  r = overlap(rect(0, 0, 1, 1), tri);
  EXPECT_EQ(r.kind, Kind::none);
  EXPECT_EQ(r.area, 0.0);
  // ...and poking in by 1e-7: a triangle of base ~1e-7 and height 1e-7, area 5e-15 < eps_A.
  const Polygon tri2{Vec2(0.5, 1.0 - 1e-7), Vec2(1.0, 2.0), Vec2(0.0, 2.0)};
  r = overlap(rect(0, 0, 1, 1), tri2);
  expect_well_formed(r, Vec2(0.5, 0.5), geo::centroid(tri2));
  EXPECT_EQ(r.kind, Kind::none);
}

TEST(Overlap, NoOverlap) {
  const auto r = overlap(rect(0, 0, 1, 1), regular(6, 0.5, Vec2(3, 0.2), 0.1));
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(3, 0.2));
  EXPECT_EQ(r.kind, Kind::none);
  EXPECT_EQ(r.crossings, 0);
}

TEST(Overlap, OneInsideTheOther) {
  const Polygon outer = regular(6, 1.0, Vec2(0, 0), 0.2);
  const Polygon inner = rect(0.1, -0.3, 0.4, 0.5);
  const Vec2 co = geo::centroid(outer), cin(0.3, -0.05);
  for (int swap = 0; swap < 2; ++swap) {
    SCOPED_TRACE(swap);
    const Polygon& pi = swap ? inner : outer;
    const Polygon& pj = swap ? outer : inner;
    const Vec2 ci = swap ? cin : co, cj = swap ? co : cin;
    const auto r = convex_overlap(pi, pj, ci, cj, 1.0);
    expect_well_formed(r, ci, cj);
    EXPECT_EQ(r.kind, Kind::enclosed);
    EXPECT_NEAR(r.area, 0.2, 1e-15);
    EXPECT_EQ(r.crossings, 0);
    EXPECT_NEAR((r.point - cin).norm(), 0.0, 1e-15);
    EXPECT_EQ(r.p1, r.point);
    EXPECT_NEAR((r.normal - (cj - ci).normalized()).norm(), 0.0, 1e-15);
  }
  // Inside and touching: in a corner (two shared edges), and with a vertex on the outer boundary.
  const Polygon big = rect(0, 0, 1, 1);
  for (const Polygon& small :
       {rect(0, 0, 0.3, 0.2), rect(0.7, 0.8, 0.3, 0.2), Polygon{Vec2(0.5, 0.0), Vec2(0.7, 0.5), Vec2(0.3, 0.5)},
        Polygon{Vec2(0.2, 0.2), Vec2(1.0, 0.5), Vec2(0.2, 0.8)}}) {
    const double a = geo::signed_area(small);
    for (int swap = 0; swap < 2; ++swap) {
      const auto r = swap ? overlap(small, big) : overlap(big, small);
      if (swap) {
        expect_well_formed(r, geo::centroid(small), Vec2(0.5, 0.5));
      } else {
        expect_well_formed(r, Vec2(0.5, 0.5), geo::centroid(small));
      }
      EXPECT_EQ(r.kind, Kind::enclosed) << small[0].transpose() << " swap " << swap;
      EXPECT_NEAR(r.area, a, 1e-15);
      EXPECT_NEAR((r.point - geo::centroid(small)).norm(), 0.0, 1e-15);
    }
  }
}

TEST(Overlap, IdenticalPolygons) {
  for (const Polygon& p : {regular(6, 1.0, Vec2(1e3, 1e3), 0.3), rect(0, 0, 1, 1), regular(7, 0.01, Vec2(0.1, 0.2))}) {
    const Vec2 c = geo::centroid(p);
    const double a = geo::signed_area(p);
    geo::OverlapPolygon ov;
    const auto r = convex_overlap(p, p, c, c, std::sqrt(a), ov);
    expect_well_formed(r, c, c);
    EXPECT_EQ(r.kind, Kind::enclosed);
    EXPECT_NEAR(r.area, a, 1e-14 * a);
    EXPECT_EQ(r.normal, Vec2(1, 0));  // documented fallback when the centroids coincide
    EXPECT_NEAR((r.point - c).norm(), 0.0, 1e-12 * std::sqrt(a));
    EXPECT_EQ(ov.size, p.size());
  }
  // Identical shapes with distinct centroids given: the normal follows c_j - c_i.
  const Polygon sq = rect(0, 0, 1, 1);
  const auto r = convex_overlap(sq, sq, Vec2(0.5, 0.5), Vec2(0.5, 0.6), 1.0);
  EXPECT_EQ(r.kind, Kind::enclosed);
  EXPECT_NEAR((r.normal - Vec2(0, 1)).norm(), 0.0, 1e-15);
}

TEST(Overlap, NearParallelEdgesOverlapping1em12) {
  // P_j's bottom edge 1e-12 below P_i's top edge, over a length 2.8: A_ov = 2.8e-12 > eps_A = 1e-12.
  const double gap = 1e-12;
  const Polygon pi = rect(0, 0, 4, 1);
  for (double tilt : {0.0, 1e-13, -1e-13}) {
    SCOPED_TRACE(tilt);
    // Bottom edge from (1.2, 1 - gap) to (5.2, 1 - gap + tilt): near-parallel, still below y = 1.
    const Polygon pj{Vec2(1.2, 1.0 - gap), Vec2(5.2, 1.0 - gap + tilt), Vec2(5.2, 2.0), Vec2(1.2, 2.0)};
    const auto r = overlap(pi, pj);
    expect_well_formed(r, geo::centroid(pi), geo::centroid(pj));
    EXPECT_EQ(r.kind, Kind::line);
    // The thickness 1 - (1 - gap) is exact (Sterbenz); its value in doubles differs from 1e-12 by
    // ~1e-16 absolute, i.e. 1e-4 relative. The computed area is checked against that thickness.
    const double t0 = 1.0 - pj[0].y(), t1 = 1.0 - (pj[0].y() + tilt * 2.8 / 4.0);
    // The crossings carry ~ulp(1) = 2.2e-16 in y: the area to 1e-15 absolute (4e-4 relative).
    EXPECT_NEAR(r.area, 2.8 * 0.5 * (t0 + t1), 1e-15);
    EXPECT_NEAR((r.normal - Vec2(0, 1)).norm(), 0.0, 1e-11);
    EXPECT_NEAR(r.point.y(), 1.0, 1e-11);
    EXPECT_NEAR(r.point.x(), 2.6, 1e-11);
  }
}

TEST(Overlap, NearParallelEdgesSeparated1em12) {
  const Polygon pi = rect(0, 0, 4, 1);
  for (double tilt : {0.0, 1e-13, -1e-13}) {
    const Polygon pj{Vec2(1.2, 1.0 + 1e-12), Vec2(5.2, 1.0 + 1e-12 + tilt), Vec2(5.2, 2.0), Vec2(1.2, 2.0)};
    const auto r = overlap(pi, pj);
    expect_well_formed(r, geo::centroid(pi), geo::centroid(pj));
    EXPECT_EQ(r.kind, Kind::none);
  }
}

// The separating-edge test with the caller's hint (the vertex that lay deepest at the last test) answers as the
// full test does, from any hint, on random convex polygons at distances from well apart to well overlapping, with
// slacks from 0 to large; and it leaves the hint on the deepest vertex, from which the next test looks at three.
TEST(Overlap, SeparatingEdgeFromTheDeepestVertexAgreesWithTheFullTest) {
  frac::Rng rng(17);
  int separated = 0, tests = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Polygon p = random_convex(rng, Vec2(0, 0), 1.0);
    const Polygon q = random_convex(rng, Vec2(rng.uniform(-3, 3), rng.uniform(-3, 3)), 1.0);
    const double slack = trial % 3 == 0 ? 0.0 : rng.uniform(0.0, 0.3);
    for (std::size_t edge = 0; edge < p.size(); ++edge) {
      const bool full = geo::edge_separates(p, edge, q, slack);
      for (std::size_t start = 0; start <= q.size(); ++start) {  // (start == q.size(): a hint out of range)
        auto hint = static_cast<std::uint8_t>(start);
        ASSERT_EQ(geo::edge_separates(p, edge, q, slack, hint), full) << "trial " << trial << " edge " << edge;
        // The hint now names a deepest vertex: no vertex of q lies deeper along the edge's normal.
        const Vec2 e = p[(edge + 1) % p.size()] - p[edge];
        auto inward = [&](const Vec2& v) { return e.x() * (v.y() - p[edge].y()) - e.y() * (v.x() - p[edge].x()); };
        ASSERT_LT(hint, q.size());
        for (const Vec2& v : q) EXPECT_GE(inward(q[hint]), inward(v));
        ++tests;
        separated += full;
      }
    }
  }
  EXPECT_GT(separated, tests / 4);
  EXPECT_LT(separated, tests * 3 / 4 + tests / 5);
}

TEST(Overlap, SliversAroundTheAreaTolerance) {
  const Polygon pi = rect(0, 0, 1, 1);
  // 1e-12 deep over a length 0.5: 5e-13 < eps_A = 1e-12 (g = 1): none.
  auto r = overlap(pi, rect(0.5, 1.0 - 1e-12, 1, 1));
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(1.0, 1.5));
  EXPECT_EQ(r.kind, Kind::none);
  // The same sliver with g = 0.1 (eps_A = 1e-14): a contact, normal along y.
  r = convex_overlap(pi, rect(0.5, 1.0 - 1e-12, 1, 1), Vec2(0.5, 0.5), Vec2(1.0, 1.5 - 1e-12), 0.1);
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR((r.normal - Vec2(0, 1)).norm(), 0.0, 1e-11);
  // A thin sliver 1e-6 deep, offset sideways: area 0.7e-6, contact line along the sliver.
  const Polygon pj = rect(0.3, 1.0 - 1e-6, 1, 1);
  r = overlap(pi, pj);
  expect_well_formed(r, Vec2(0.5, 0.5), geo::centroid(pj));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.7e-6, 1e-16);
  expect_same_pair(r.p1, r.p2, Vec2(1.0, 1.0 - 1e-6), Vec2(0.3, 1.0), 1e-15);
  EXPECT_NEAR((r.normal - Vec2(0, 1)).norm(), 0.0, 1e-5);  // tilted by 1e-6/0.7
  // A wedge: P_j's bottom tilted by 1e-3 rad, 1e-3 deep at x = 0.2 and 0.2e-3 deep at x = 1.
  const Polygon wedge{Vec2(0.2, 1.0 - 1e-3), Vec2(1.2, 1.0), Vec2(1.2, 2.0), Vec2(0.2, 2.0)};
  r = overlap(pi, wedge);
  expect_well_formed(r, Vec2(0.5, 0.5), geo::centroid(wedge));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.8 * 0.5 * (1e-3 + 0.2e-3), 1e-15);
}

TEST(Overlap, CollinearOverlappingEdges) {
  // Squares offset along x: their top and bottom edges overlap on [0.5, 1]. The crossings are the
  // midpoints of the shared runs, (0.75, 0) and (0.75, 1): the same answer whichever is i.
  const Polygon pi = rect(0, 0, 1, 1), pj = rect(0.5, 0, 1, 1);
  const auto r = overlap(pi, pj);
  expect_well_formed(r, Vec2(0.5, 0.5), Vec2(1.0, 0.5));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.5, 1e-15);
  expect_same_pair(r.p1, r.p2, Vec2(0.75, 0.0), Vec2(0.75, 1.0), 1e-15);
  EXPECT_NEAR((r.normal - Vec2(1, 0)).norm(), 0.0, 1e-15);
  const auto s = overlap(pj, pi);
  EXPECT_NEAR((s.point - r.point).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.normal + r.normal).norm(), 0.0, 1e-15);
  // Stacked cells of a square grid pressed together: the sides are collinear, the overlap is a thin
  // strip, the contact line runs along it through the middles of the short sides.
  const Polygon up = rect(0, 1.0 - 1e-4, 1, 1);
  const auto t = overlap(pi, up);
  EXPECT_EQ(t.kind, Kind::line);
  EXPECT_NEAR(t.area, 1e-4, 1e-15);
  expect_same_pair(t.p1, t.p2, Vec2(0.0, 1.0 - 0.5e-4), Vec2(1.0, 1.0 - 0.5e-4), 1e-15);
  EXPECT_NEAR((t.normal - Vec2(0, 1)).norm(), 0.0, 1e-15);
  // The same, with the sides off by 1e-13 (near-collinear, within eps_L = 1e-12 g, 500 times the round-off of
  // coordinates ~1): the same answer to 1e-11.
  const auto u = overlap(pi, rect(1e-13, 1.0 - 1e-4, 1, 1));
  EXPECT_EQ(u.kind, Kind::line);
  EXPECT_NEAR((u.normal - Vec2(0, 1)).norm(), 0.0, 1e-11);
  EXPECT_NEAR((u.point - Vec2(0.5, 1.0 - 0.5e-4)).norm(), 0.0, 1e-11);
  // Off by 1e-10 instead: well beyond eps_L near the origin, so the boundaries cross at j's corner (the contact
  // line from (1e-10, 1 - 1e-4) to (1, 1), turned by 1e-4 rad)...
  const auto w = overlap(pi, rect(1e-10, 1.0 - 1e-4, 1, 1));
  EXPECT_EQ(w.kind, Kind::line);
  EXPECT_GT((w.normal - Vec2(0, 1)).norm(), 0.5e-4);
  // ...but 1e6 g from the origin, where the coordinates' round-off is ~1e-10 (ulp(1e6) = 1.2e-10), an offset of
  // 1e-10 is round-off: eps_L grows to 64 ulps of the coordinates, 1.4e-8, and the sides count as collinear.
  const Vec2 far(1e6, -1e6);
  Polygon pi_far = pi, up_far = rect(1e-10, 1.0 - 1e-4, 1, 1);
  for (Vec2& p : pi_far) p += far;
  for (Vec2& p : up_far) p += far;
  const auto x = convex_overlap(pi_far, up_far, geo::centroid(pi_far), geo::centroid(up_far), 1.0);
  EXPECT_EQ(x.kind, Kind::line);
  EXPECT_NEAR((x.normal - Vec2(0, 1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((x.point - far - Vec2(0.5, 1.0 - 0.5e-4)).norm(), 0.0, 1e-9);
  // A corner region shared: small square in P_i's corner but sticking out on one side.
  const auto v = overlap(pi, rect(0.5, 0, 1, 0.5));
  expect_well_formed(v, Vec2(0.5, 0.5), Vec2(1.0, 0.25));
  EXPECT_EQ(v.kind, Kind::line);
  EXPECT_NEAR(v.area, 0.25, 1e-15);
  expect_same_pair(v.p1, v.p2, Vec2(0.75, 0.0), Vec2(1.0, 0.5), 1e-15);
}

TEST(Overlap, CollinearEdgesRotatedStayCollinearToRoundOff) {
  // The two cases above, rotated and moved: the edges are collinear only to round-off, so the
  // clipper makes near-duplicate vertices and tiny edges with either label along the shared runs.
  // The answer must still be the rotated one, to within eps_L = 1e-9, and symmetric under i <-> j.
  const Vec2 shift(12.3, -7.1), pivot(0, 0);
  for (int k = 0; k < 64; ++k) {
    const double angle = 0.1 * k;
    SCOPED_TRACE(angle);
    const Polygon pi = moved(rect(0, 0, 1, 1), angle, pivot, shift);
    const Polygon pj = moved(rect(0.5, 0, 1, 1), angle, pivot, shift);
    const auto r = overlap(pi, pj), s = overlap(pj, pi);
    expect_well_formed(r, geo::centroid(pi), geo::centroid(pj));
    EXPECT_EQ(r.kind, Kind::line);
    EXPECT_EQ(r.distinct_crossings, 2);
    EXPECT_NEAR(r.area, 0.5, 1e-14);
    expect_same_pair(r.p1, r.p2, rotate(Vec2(0.75, 0), angle) + shift, rotate(Vec2(0.75, 1), angle) + shift, 1e-9);
    EXPECT_NEAR((r.normal - rotate(Vec2(1, 0), angle)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((s.normal + r.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR((s.point - r.point).norm(), 0.0, 1e-9);
    // Stacked grid cells pressed by 1e-4.
    const Polygon up = moved(rect(0, 1.0 - 1e-4, 1, 1), angle, pivot, shift);
    const auto t = overlap(pi, up);
    EXPECT_EQ(t.kind, Kind::line);
    EXPECT_EQ(t.distinct_crossings, 2);
    EXPECT_NEAR((t.normal - rotate(Vec2(0, 1), angle)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((t.point - (rotate(Vec2(0.5, 1.0 - 0.5e-4), angle) + shift)).norm(), 0.0, 1e-9);
  }
}

TEST(Overlap, CornerPokingThroughUsesFarthestPair) {
  // A triangle through a thin rectangle: four crossings (1.5, 0), (1.6, 0.2), (2.4, 0.2), (2.5, 0).
  // The farthest pair is the bottom one; the area is the whole trapezoid, (1.0 + 0.8)/2 * 0.2.
  const Polygon bar = rect(0, 0, 4, 0.2);
  const Polygon tri{Vec2(1, -1), Vec2(3, -1), Vec2(2, 1)};
  const Vec2 cb(2, 0.1), ct(2, -1.0 / 3.0);
  const auto r = convex_overlap(bar, tri, cb, ct, 1.0);
  expect_well_formed(r, cb, ct);
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_EQ(r.crossings, 4);
  EXPECT_EQ(r.distinct_crossings, 4);
  EXPECT_NEAR(r.area, 0.18, 1e-15);
  expect_same_pair(r.p1, r.p2, Vec2(1.5, 0), Vec2(2.5, 0), 1e-15);
  EXPECT_NEAR((r.normal - Vec2(0, -1)).norm(), 0.0, 1e-15);
  const auto s = convex_overlap(tri, bar, ct, cb, 1.0);
  EXPECT_EQ(s.distinct_crossings, 4);
  EXPECT_NEAR(s.area, r.area, 1e-15);
  EXPECT_NEAR((s.normal + r.normal).norm(), 0.0, 1e-15);
}

TEST(Overlap, PolygonWithTinyEdge) {
  // Unit square with its (1,1) corner cut by an edge 1e-9 * sqrt(2) long.
  const double e = 1e-9;
  const Polygon cut{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1 - e), Vec2(1 - e, 1), Vec2(0, 1)};
  ASSERT_TRUE(geo::is_convex_ccw(cut));
  // The half-plane y <= x cuts through the tiny edge's midpoint and through vertex (0,0).
  const Polygon lower{Vec2(-1, -1), Vec2(3, -1), Vec2(3, 3)};
  auto r = overlap(cut, lower);
  expect_well_formed(r, geo::centroid(cut), geo::centroid(lower));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.5 - 0.25 * e * e, 1e-15);
  // The piece of the tiny edge inside the overlap is shorter than eps_L = 1e-9: it counts as on both
  // boundaries, which may move the crossing along it by up to eps_L/2.
  expect_same_pair(r.p1, r.p2, Vec2(0, 0), Vec2(1 - 0.5 * e, 1 - 0.5 * e), 1e-9);
  EXPECT_NEAR((r.normal - Vec2(1, -1) / std::sqrt(2.0)).norm(), 0.0, 1e-9);
  // A square whose corner sits on the tiny edge: overlap ~1e-18, none.
  r = overlap(cut, rect(1 - 0.5 * e, 1 - 0.5 * e, 1, 1));
  expect_well_formed(r, geo::centroid(cut), Vec2(1.5, 1.5));
  EXPECT_EQ(r.kind, Kind::none);
  // A square overlapping the cut corner by 0.25: both crossings away from the tiny edge.
  r = overlap(cut, rect(0.5, 0.5, 1, 1));
  EXPECT_EQ(r.kind, Kind::line);
  EXPECT_NEAR(r.area, 0.25 - 0.5 * e * e, 1e-15);
  expect_same_pair(r.p1, r.p2, Vec2(1, 0.5), Vec2(0.5, 1), 1e-15);
  // Two copies turned by pi so that the tiny edges face each other: 0.7e-9 apart, touching
  // (collinear, opposite orientation), and pressed 1e-9 into each other (overlap ~1e-18): none.
  for (double shift : {1.0 - 0.5 * e, 1.0 - e, 1.0 - 2.0 * e}) {
    const Polygon other = moved(cut, kPi, Vec2(0.5, 0.5), Vec2(shift, shift));
    r = overlap(cut, other);
    expect_well_formed(r, geo::centroid(cut), geo::centroid(other));
    EXPECT_EQ(r.kind, Kind::none) << shift;
  }
}

TEST(Overlap, SwapGivesSameAreaAndOppositeNormal) {
  std::vector<std::pair<Polygon, Polygon>> pairs = {
      {rect(0, 0, 1, 1), rect(0.5, 0.25, 1, 1)},
      {regular(6, 1.0, Vec2(0, 0), 0.1), regular(6, 1.0, Vec2(1.5, 0.4), 0.5)},
      {regular(5, 0.8, Vec2(1e3, 1e3), 0.0), regular(4, 1.1, Vec2(1e3 + 0.9, 1e3 + 0.2), 0.3)},
      {rect(0, 0, 4, 0.2), Polygon{Vec2(1, -1), Vec2(3, -1), Vec2(2, 1)}},
      {rect(0, 0, 1, 1), rect(0.3, 1.0 - 1e-6, 1, 1)},
  };
  for (const auto& [a, b] : pairs) {
    const Vec2 ca = geo::centroid(a), cb = geo::centroid(b);
    const auto r = convex_overlap(a, b, ca, cb, 1.0), s = convex_overlap(b, a, cb, ca, 1.0);
    expect_well_formed(r, ca, cb);
    expect_well_formed(s, cb, ca);
    EXPECT_EQ(r.kind, s.kind);
    EXPECT_NEAR(r.area, s.area, 1e-12 * r.area);
    EXPECT_NEAR((r.normal + s.normal).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.point - s.point).norm(), 0.0, 1e-12);
  }
}

TEST(Overlap, RandomPairsAgreeWithClippingAndBruteForceCrossings) {
  // Random convex polygons: the area matches clip_convex, the contact line joins the boundary
  // crossings found by brute force over all edge pairs, and swapping i and j flips the normal.
  frac::Rng rng(2024);
  int lines = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 base(rng.uniform(-50, 50), rng.uniform(-50, 50));
    const Polygon a = random_convex(rng, base, 1.0);
    const Polygon b = random_convex(rng, base + Vec2(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)), 1.0);
    const Vec2 ca = geo::centroid(a), cb = geo::centroid(b);
    const auto r = convex_overlap(a, b, ca, cb, 1.0);
    expect_well_formed(r, ca, cb);
    const double ref = geo::signed_area(geo::clip_convex(a, b));
    if (r.kind == Kind::none) {
      EXPECT_LE(ref, 1e-12);
      continue;
    }
    EXPECT_NEAR(r.area, ref, 1e-13 * std::max(1.0, ref));
    const auto s = convex_overlap(b, a, cb, ca, 1.0);
    EXPECT_NEAR(s.area, r.area, 1e-13);
    EXPECT_NEAR((s.normal + r.normal).norm(), 0.0, 1e-9);
    const auto bf = brute_force_crossings(a, b);
    EXPECT_EQ(static_cast<std::size_t>(r.crossings), bf.size());
    if (r.kind == Kind::line && bf.size() == 2) {
      ++lines;
      expect_same_pair(r.p1, r.p2, bf[0], bf[1], 1e-12);
      EXPECT_LE(distance_to_boundary(r.p1, a), 1e-12);
      EXPECT_LE(distance_to_boundary(r.p2, b), 1e-12);
      EXPECT_NEAR(r.normal.dot(r.p2 - r.p1), 0.0, 1e-12);
    }
    if (r.kind == Kind::enclosed) {
      EXPECT_TRUE(bf.empty());
    }
  }
  EXPECT_GT(lines, 500);
}

TEST(Overlap, RejectsBadInput) {
  const Polygon big = regular(40, 0.1, Vec2(0, 0));
  EXPECT_THROW(overlap(big, rect(0, 0, 1, 1)), frac::InputError);
  EXPECT_THROW(convex_overlap(rect(0, 0, 1, 1), rect(0, 0, 1, 1), Vec2(0, 0), Vec2(0, 0), 0.0), frac::InputError);
  // Fewer than 3 vertices: no contact.
  EXPECT_EQ(overlap(Polygon{Vec2(0, 0), Vec2(1, 1)}, rect(0, 0, 1, 1)).kind, Kind::none);
}

}  // namespace

// The reach of an edge (overlap.hpp): every point within it of the edge's midpoint is inside the
// half-plane of every edge but the edge and its two neighbours, by at least 1e-3 of the reach.
TEST(Overlap, EdgeReachKeepsPointsInsideTheOtherEdges) {
  frac::Rng rng(77);
  int with_reach = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Polygon p = random_convex(rng, Vec2(rng.uniform(-5, 5), rng.uniform(-5, 5)), 1.0);
    const std::size_t m = p.size();
    for (std::size_t e = 0; e < m; ++e) {
      const double reach = frac::geometry::edge_reach(p, e);
      ASSERT_GE(reach, 0.0);
      if (reach == 0.0) continue;
      ++with_reach;
      const Vec2 mid = 0.5 * (p[e] + p[(e + 1) % m]);
      for (int s = 0; s < 20; ++s) {
        // Points on the circle of the reach (the worst case) and inside it.
        const double angle = rng.uniform(0, 2 * std::numbers::pi), r = s < 10 ? reach : rng.uniform(0, reach);
        const Vec2 x = mid + r * Vec2(std::cos(angle), std::sin(angle));
        for (std::size_t c = 0; c < m; ++c) {
          const std::size_t gap = c > e ? c - e : e - c;
          if (gap <= 1 || gap == m - 1) continue;
          const Vec2 d = p[(c + 1) % m] - p[c];
          EXPECT_GE(geo::cross(d, x - p[c]) / d.norm(), 0.999e-3 * reach) << "trial " << trial;
        }
      }
    }
  }
  EXPECT_GT(with_reach, 1000);
  // A triangle has no edge but the neighbours of each: every point of the plane is within the reach.
  EXPECT_EQ(frac::geometry::edge_reach(Polygon{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, 0),
            std::numeric_limits<double>::infinity());
}

namespace {

// Whether two contact geometries agree in every field, bit for bit.
::testing::AssertionResult same_bits(const ContactGeometry& a, const ContactGeometry& b) {
  if (a.kind != b.kind || a.area != b.area || a.crossings != b.crossings ||
      a.distinct_crossings != b.distinct_crossings)
    return ::testing::AssertionFailure() << "kind, area or crossings differ: area " << a.area << " against " << b.area;
  for (const auto& [u, v] : {std::pair{a.p1, b.p1}, {a.p2, b.p2}, {a.point, b.point}, {a.normal, b.normal}}) {
    if (u.x() != v.x() || u.y() != v.y())
      return ::testing::AssertionFailure()
             << "(" << u.x() << ", " << u.y() << ") against (" << v.x() << ", " << v.y() << ")";
  }
  return ::testing::AssertionSuccess();
}

// A random lattice of side × side cells, 1.07 cm apart.
frac::mesh::CellMesh square_lattice(int side, std::uint64_t seed) {
  frac::mesh::RandomLatticeOptions o;
  o.shape = "rect";
  o.nx = o.ny = side;
  o.width = o.height = side * 0.0107;
  o.seed = seed;
  return frac::mesh::make_random_lattice(o);
}

// The contact search's hint for two polygons: the edges facing each other's centroid and their reaches.
frac::geometry::OverlapHint facing_hint(const Polygon& pi, const Polygon& pj) {
  const Vec2 ci = geo::centroid(pi), cj = geo::centroid(pj);
  frac::geometry::OverlapHint hint;
  hint.edge_i = geo::facing_edge(pi, cj - ci);
  hint.edge_j = geo::facing_edge(pj, ci - cj);
  hint.reach_i = geo::edge_reach(pi, hint.edge_i);
  hint.reach_j = geo::edge_reach(pj, hint.edge_j);
  return hint;
}

}  // namespace

// The hint of the contact search (facing edges and their reaches) changes the work, not the result:
// every field bit for bit, for cells of a random lattice moved apart, into slivers and into deep
// overlaps, with the facing edges and with edges that face away.
TEST(Overlap, HintGivesTheSameResultBitForBit) {
  const auto mesh = square_lattice(12, 3);
  const std::size_t n = mesh.cells();
  const double g = mesh.spacing;
  std::vector<double> reach(mesh.vertex.size());
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t e = 0; e < mesh.polygon(k).size(); ++e)
      reach[static_cast<std::size_t>(mesh.vertex_offset[k]) + e] = frac::geometry::edge_reach(mesh.polygon(k), e);
  frac::Rng rng(11);
  int overlapping = 0, pairs = 0;
  for (const double jiggle : {1e-4, 3e-3, 3e-2, 0.2}) {
    std::vector<std::vector<Vec2>> world(n);
    std::vector<Vec2> centre(n);
    for (std::size_t k = 0; k < n; ++k) {
      centre[k] = mesh.centroid[k] + jiggle * g * Vec2(rng.uniform(-1, 1), rng.uniform(-1, 1));
      const double phi = jiggle * rng.uniform(-1, 1), c = std::cos(phi), s = std::sin(phi);
      for (const Vec2& p : mesh.polygon(k))
        world[k].push_back(centre[k] + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
    }
    for (const auto& beam : mesh.beam) {
      const auto i = static_cast<std::size_t>(beam[0]), j = static_cast<std::size_t>(beam[1]);
      for (int variant = 0; variant < 3; ++variant) {
        frac::geometry::OverlapHint hint;
        const Vec2 d = centre[j] - centre[i];
        hint.edge_i = frac::geometry::facing_edge(world[i], d);
        hint.edge_j = frac::geometry::facing_edge(world[j], -d);
        if (variant == 1) hint.edge_i = (hint.edge_i + 2) % world[i].size();  // a hint that does not face
        if (variant == 2) hint.edge_j = (hint.edge_j + 3) % world[j].size();
        hint.reach_i = reach[static_cast<std::size_t>(mesh.vertex_offset[i]) + hint.edge_i];
        hint.reach_j = reach[static_cast<std::size_t>(mesh.vertex_offset[j]) + hint.edge_j];
        const auto plain = convex_overlap(world[i], world[j], centre[i], centre[j], g, hint.edge_j);
        const auto fast = convex_overlap(world[i], world[j], centre[i], centre[j], g, hint);
        ++pairs;
        overlapping += plain.kind != Kind::none;
        ASSERT_TRUE(same_bits(fast, plain));
      }
    }
  }
  EXPECT_GT(overlapping, pairs / 3);
}

// The hinted path tests shared edges against the three lines next to each facing edge only: cells whose sides
// are collinear (a straight outer boundary, stacked grid cells), turned against each other by angles from 0
// to 1e-2, and moved as a pair, give the same result bit for bit with and without the hint, shared runs
// included; so does an overlap edge shorter than tol next to a crossing (shared by its length).
TEST(Overlap, HintGivesTheSameResultOnSharedEdges) {
  frac::Rng rng(5);
  const Polygon base_i = rect(0, 0, 1, 1);
  int shared_runs = 0;
  for (const double turn : {0.0, 1e-13, 1e-10, 1e-7, 5e-4, 2e-3, 1e-2}) {
    for (const Polygon& base_j :
         {rect(0.9, 0, 1, 1), rect(0.5, 0, 1, 1), rect(0, 0.99, 1, 1), rect(0.3, 0.999, 1, 1)}) {
      for (int trial = 0; trial < 20; ++trial) {
        // The pair turned and moved as a whole, then j turned by `turn` about the middle of the overlap.
        const double angle = trial == 0 ? 0.0 : rng.uniform(-3, 3);
        const Vec2 shift = trial == 0 ? Vec2::Zero() : Vec2(rng.uniform(-10, 10), rng.uniform(-10, 10));
        const Vec2 pivot = 0.5 * (base_j[0] + base_i[2]);
        const Polygon pi = moved(base_i, angle, Vec2::Zero(), shift);
        const Polygon pj = moved(moved(base_j, turn, pivot, Vec2::Zero()), angle, Vec2::Zero(), shift);
        const Vec2 ci = geo::centroid(pi), cj = geo::centroid(pj);
        const auto hint = facing_hint(pi, pj);
        const auto plain = convex_overlap(pi, pj, ci, cj, 1.0, hint.edge_j);
        const auto fast = convex_overlap(pi, pj, ci, cj, 1.0, hint);
        ASSERT_NE(plain.kind, Kind::none);
        if (turn == 0.0 && trial == 0 && base_j[0].y() == 0.0) {
          // Side by side: the crossings are the middles of the shared bottom and top runs [x0, 1].
          const double mid = 0.5 * (base_j[0].x() + 1.0);
          shared_runs += std::abs(plain.p1.x() - mid) < 1e-12 && std::abs(plain.p2.x() - mid) < 1e-12;
        }
        ASSERT_TRUE(same_bits(fast, plain)) << "turn " << turn << " trial " << trial;
      }
    }
  }
  // The unmoved side-by-side squares put their crossings at the middles of the shared runs.
  EXPECT_EQ(shared_runs, 2);
  // A corner of j 1e-13 inside i's right side: the overlap edge from it to the crossing is shorter than eps_L
  // (1e-12 here), which makes it shared whatever the angles (the crossing moves to the middle of that edge).
  const Polygon pj = {Vec2(1 - 1e-6, 0.6), Vec2(1 - 1e-13, 0.3), Vec2(2.4, 0.25), Vec2(2.4, 0.65)};
  const Vec2 ci = geo::centroid(base_i), cj = geo::centroid(pj);
  const auto hint = facing_hint(base_i, pj);
  ASSERT_EQ(hint.edge_j, 0u);
  ASSERT_GT(hint.reach_j, 1.0);  // the whole side of i that line 0 cuts off lies within it: the hinted path
  const auto plain = convex_overlap(base_i, pj, ci, cj, 1.0, hint.edge_j);
  const auto fast = convex_overlap(base_i, pj, ci, cj, 1.0, hint);
  ASSERT_EQ(plain.kind, Kind::line);
  EXPECT_TRUE(same_bits(fast, plain));
  // The crossing is the middle of the short edge, half of 1e-13 in from the side.
  EXPECT_EQ(std::min(plain.p1.x(), plain.p2.x()), 0.5 * ((1 - 1e-13) + 1.0));
}

// A pair's cache of the lines of its last overlap (the contact search keeps one per neighbour pair) changes the
// work, not the result: cells of a random lattice random-walk for 60 steps, each bonded pair carrying its
// cache from step to step (and, every seventh step, another pair's cache instead of its own), and every
// result equals the one computed without hint or cache (clipping in the same order), bit for bit. Most
// overlaps keep their lines from one step to the next, so most evaluations use the cache.
TEST(Overlap, CachedLinesGiveTheSameResultBitForBit) {
  const auto mesh = square_lattice(10, 8);
  const std::size_t n = mesh.cells();
  const double g = mesh.spacing;
  frac::Rng rng(21);
  std::vector<Vec2> centre(mesh.centroid.begin(), mesh.centroid.end());
  std::vector<double> phi(n, 0.0);
  std::vector<frac::geometry::OverlapLines> cache(mesh.beam.size());
  int overlapping = 0, kept = 0;
  for (int step = 0; step < 60; ++step) {
    std::vector<std::vector<Vec2>> world(n);
    for (std::size_t k = 0; k < n; ++k) {
      centre[k] += 2e-4 * g * Vec2(rng.uniform(-1, 1), rng.uniform(-1, 1));
      phi[k] += 2e-4 * rng.uniform(-1, 1);
      const double c = std::cos(phi[k]), s = std::sin(phi[k]);
      for (const Vec2& p : mesh.polygon(k))
        world[k].push_back(centre[k] + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
    }
    for (std::size_t b = 0; b < mesh.beam.size(); ++b) {
      const auto i = static_cast<std::size_t>(mesh.beam[b][0]), j = static_cast<std::size_t>(mesh.beam[b][1]);
      frac::geometry::OverlapHint hint = facing_hint(world[i], world[j]);
      frac::geometry::OverlapLines lines = step % 7 == 3 ? cache[(b + 1) % cache.size()] : cache[b];
      const frac::geometry::OverlapLines before = lines;
      hint.lines = &lines;
      const auto fast = convex_overlap(world[i], world[j], centre[i], centre[j], g, hint);
      const auto plain = convex_overlap(world[i], world[j], centre[i], centre[j], g, hint.edge_j);
      ASSERT_TRUE(same_bits(fast, plain)) << "step " << step << " beam " << b;
      cache[b] = lines;
      if (plain.kind == Kind::none) continue;
      ++overlapping;
      kept += before.size >= 3 && before.size == lines.size && before.label == lines.label;
    }
  }
  EXPECT_GT(overlapping, 5000);
  EXPECT_GT(kept, overlapping / 2);
}
