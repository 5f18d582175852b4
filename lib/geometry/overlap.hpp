#pragma once
// Overlap of two convex polygons for the DEM contact law (polygon-dem.md section 3): the overlap
// area A_ov, the points P1, P2 where the two boundaries cross, the application point R and the
// unit normal n. Allocation-free: all work is done in fixed-capacity buffers on the stack.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "geometry/vec2.hpp"

namespace frac::geometry {

// Largest polygon convex_overlap accepts (Voronoi cells of the lattice have at most ~15 sides).
inline constexpr std::size_t kMaxContactPolygonVertices = 32;
// Capacity of the overlap polygon. A convex n-gon clipped by m half-planes has at most n + m
// vertices; the margin absorbs near-duplicate vertices made by round-off.
inline constexpr std::size_t kMaxOverlapVertices = 4 * kMaxContactPolygonVertices;

// Tolerances in units of the length scale g (the cell size): eps_A = kOverlapAreaTolerance * g^2, and
// eps_L = kCrossingMergeTolerance * g, or kCrossingMergeUlps times the largest coordinate of the two polygons'
// first vertices where that is larger (crossing_merge_tolerance). eps_L only tames round-off (touching vertices,
// collinear edges). A world coordinate x carries a few ulps of round-off, 2^-52 |x| each; eps_L stays 16 times
// above that however far from the origin the cells lie: 1e-12 g up to |x| = 70 g, then 2^-46 |x|. (The physics
// note suggests "about 1e-9 g". With 1e-9 g, every thin sliver between bonded neighbours turned against each
// other by less than ~4e-9 rad had an edge shorter than the margin of a regular overlap, 4 eps_L, and was
// clipped: a third of the overlaps of the 10^4-cell benchmark, half its contact geometry's time.)
inline constexpr double kOverlapAreaTolerance = 1e-12;
inline constexpr double kCrossingMergeTolerance = 1e-12;
inline constexpr double kCrossingMergeUlps = 0x1p-46;  // 64 ulps
// eps_L (m) for polygons whose first vertices are a and b (m), with length scale g (m).
inline double crossing_merge_tolerance(double g, const Vec2& a, const Vec2& b) {
  const double extent =
      std::max(std::max(std::abs(a.x()), std::abs(a.y())), std::max(std::abs(b.x()), std::abs(b.y())));
  return std::max(kCrossingMergeTolerance * g, kCrossingMergeUlps * extent);
}

// The overlap polygon P_i ∩ P_j (counter-clockwise), in the caller's coordinates.
struct OverlapPolygon {
  std::array<Vec2, kMaxOverlapVertices> vertex;
  std::size_t size = 0;
  std::span<const Vec2> vertices() const { return {vertex.data(), size}; }
};

struct ContactGeometry {
  // none: no contact force (A_ov <= eps_A). line: the boundaries cross; the force acts at the
  // midpoint of the contact line P1P2. enclosed: overlap without a contact line (one polygon inside
  // the other, identical polygons); the force acts at the overlap centroid, along c_j - c_i.
  enum class Kind { none, line, enclosed };
  Kind kind = Kind::none;
  double area = 0.0;       // A_ov (m^2); 0 when kind == none
  Vec2 p1 = Vec2::Zero();  // contact line P1P2 (m); p1 = p2 = point when enclosed
  Vec2 p2 = Vec2::Zero();
  Vec2 point = Vec2::Zero();   // application point R (m)
  Vec2 normal = Vec2::Zero();  // unit normal from i toward j, n·(c_j - c_i) >= 0; zero when none
  int crossings = 0;           // boundary crossings found, before cancelling coincident pairs (0 if none)
  int distinct_crossings = 0;  // after cancelling; > 2 means a corner poked through (overlap too large)
};

// Contact geometry of the convex counter-clockwise polygons P_i and P_j (at most
// kMaxContactPolygonVertices each) with centroids c_i and c_j. `length_scale` g > 0 (the cell size)
// sets the tolerances eps_A and eps_L. Every result is finite for finite input.
//
// Method. P = P_i ∩ P_j by Sutherland-Hodgman (P_i clipped by the half-planes of P_j's edges, no
// tolerance, so A_ov is exact up to round-off; computed about P_i's first vertex, so far translation
// costs no accuracy). Each edge of P is labelled with the polygon whose boundary it lies on. A
// crossing is a vertex of P where the label changes. An edge of P that lies on both boundaries
// (collinear edges of the same orientation, within eps_L; or an edge shorter than eps_L) belongs to
// neither: a crossing next to such a run of edges is moved to the midpoint of the run. Two crossings
// adjacent along the boundary of P and closer than eps_L are an excursion of one boundary that does
// not cross the other (round-off at a touching vertex): the pair is cancelled. The count is even.
//
// Conventions for the degenerate cases (polygon-dem.md section 3, "Degenerate cases"):
// - A_ov <= eps_A (no overlap, a shared edge, touching vertices, a sliver thinner than eps_A / length):
//   none, with area 0 and zero vectors.
// - 2 crossings: line; P1, P2 the crossings, R = (P1 + P2)/2, n ⊥ P2 - P1.
// - more than 2 crossings (a corner poking through): line with the pair of crossings farthest apart;
//   the area stays the full overlap area. distinct_crossings reports the count.
// - 0 crossings and A_ov > eps_A (one polygon inside the other, identical polygons): enclosed;
//   R = centroid of P, n = (c_j - c_i)/|c_j - c_i|, or +x when the centroids coincide.
// - 1 or 3 crossings cannot occur: crossings alternate between P_i's and P_j's boundary, so they
//   come in pairs, and cancelling removes pairs. (Were one ever left alone, it would count as 0:
//   enclosed; three would use the farthest pair.) A touching vertex gives a pair closer than eps_L,
//   which cancels: with A_ov > eps_A that is the enclosed case (a polygon inside touching the other's
//   boundary), otherwise none.
// - Collinear overlapping edges (offset squares): the crossing is the midpoint of the shared run,
//   which makes the answer symmetric under i <-> j.
// - n·(c_j - c_i) == 0 exactly for a contact line: n is the perpendicular whose first nonzero
//   component is positive.
// - Regular overlaps (the usual case) are computed from their lines. The clipped polygon is regular when it
//   has at most 8 vertices on as many different lines, every corner turns left, every edge runs along its line
//   and is longer than tol = 4 eps_L, a crossing of the boundaries lies on both its edges more than tol from
//   their ends, a corner of one polygon lies more than tol inside every edge line of the other, and the
//   boundaries cross exactly twice. Each vertex is then the intersection of its two lines (or a polygon's
//   corner itself), A_ov comes from the shoelace formula about the vertex on the line of lowest label, and P1,
//   P2 are the two vertices where the boundary changes owner. No shared edge, no cancellation and no corner
//   poking through can occur then: the conventions above give the same answer up to round-off. Because the
//   result depends on the lines alone, it is the same bit for bit whatever the path (the clip order, a hint,
//   cached lines); an irregular overlap's result may depend on the clip order at round-off.
// Throws InputError if a polygon has more than kMaxContactPolygonVertices vertices or g is not > 0.
// `first_clip_edge`: the edge of P_j to clip by first (a hint for speed: the one facing P_i; the
// result is the same up to round-off whatever the hint).
ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, std::size_t first_clip_edge = 0);

// The lines that bound a pair's overlap polygon, in order around it, as the last evaluation of the pair found
// them (edge labels: 0..n-1 the edges of P_i, n + b edge b of P_j; size 0: none known). A caller that keeps
// one per pair and hands it back in the hint lets an overlap that keeps its shape skip the clipping.
struct OverlapLines {
  std::uint8_t size = 0;
  std::array<std::uint8_t, 8> label{};
};

// A faster path for cells of a mesh, with the same result bit for bit: the facing edges of P_i and P_j
// (first vertex index; P_j is clipped by its facing edge first) and their reaches (edge_reach of the
// polygons, which a rigid motion does not change; 0: no reach known). When the overlap lies within the
// reach of a facing edge, the lines of that polygon's other edges are left out: they can neither cut it
// nor come within eps_L of it. With `lines`: the lines of a regular overlap are kept there; the next call
// intersects them first and checks the polygon they make (a regular polygon whose vertices lie inside both
// polygons is the overlap), and clips only when the check fails. Most overlaps of a time step keep their
// lines from the step before.
struct OverlapHint {
  std::size_t edge_i = 0, edge_j = 0;
  double reach_i = 0.0, reach_j = 0.0;  // m
  OverlapLines* lines = nullptr;        // the pair's cache, read and updated; none: always clip
};
ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, const OverlapHint& hint);

// The reach of edge `edge` of the convex polygon p: a radius about the edge's midpoint within which every
// point is inside the half-plane of every edge of p other than this edge and its two neighbours, by at
// least 1e-3 of the reach (a margin far above round-off). 0 when there is none (then no shortcut);
// infinite when every other edge is a neighbour (a triangle).
double edge_reach(std::span<const Vec2> p, std::size_t edge);

// The same, also returning the overlap polygon (empty when it has fewer than 3 vertices).
ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, OverlapPolygon& overlap);

}  // namespace frac::geometry
