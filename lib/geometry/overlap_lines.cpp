#include "geometry/overlap_lines.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/polygon.hpp"

namespace frac::geometry::detail {

// n perpendicular to the contact line (p2 - p1 != 0), oriented from i toward j. (The orientation from the
// unscaled perpendicular, so that it does not wait for the square root and the division; lengths ≥ eps_L ~
// 1e-11 m: no under/overflow.)
Vec2 line_normal(const Vec2& p1, const Vec2& p2, const Vec2& dc) {
  const Vec2 t = p2 - p1;
  const Vec2 m = perp(t);
  const double s = m.dot(dc);
  const bool flip = s < 0.0 || (s == 0.0 && (m.x() < 0.0 || (m.x() == 0.0 && m.y() < 0.0)));
  return m * ((flip ? -1.0 : 1.0) / std::sqrt(t.squaredNorm()));
}

// The vertices of the polygon bounded by the lines `label` [0, K) in order (edge k on line label[k], vertex k
// = line label[k−1] ∩ line label[k]; a corner of one polygon is that vertex itself) into v, when the polygon
// is regular (convex_overlap): false otherwise. Every turn is to the left, every edge runs along its line and
// is longer than tol, a crossing lies on both its edges more than tol from their ends, a corner of one
// polygon more than tol inside every edge line of the other. Such a polygon (convex: checked for five
// vertices or more, where turns to the left could wind twice) is P_i ∩ P_j: its vertices lie in both, and it
// is the intersection of the half-planes of its own edges, each of which contains P_i ∩ P_j.
bool regular_vertices(const PairEdges& edges, const int* label, std::size_t K, Vec2* v) {
  std::array<PairEdges::Line, kMaxRegularVertices> line;
  for (std::size_t k = 0; k < K; ++k) line[k] = edges.line(label[k]);
  int switches = 0;
  bool ok = true;
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t k0 = k == 0 ? K - 1 : k - 1;
    const PairEdges::Line& a = line[k0];
    const PairEdges::Line& b = line[k];
    if (edges.next(label[k0]) == label[k]) {  // a corner of one polygon
      v[k] = Vec2(b.ax, b.ay);
      ok &= edges.inside_polygon(b.ax, b.ay, !edges.of_j(label[k]));
      continue;
    }
    ++switches;
    // A crossing: a left turn by more than ~1e-12 rad (the intersection is well defined), on both edges:
    // at s_b/den along b and s_a/den along a, each more than tol from the ends (s_b·|b| > tol·den, and so on;
    // compared squared, all terms positive).
    const double den = a.dx * b.dy - a.dy * b.dx;
    const double a2 = a.dx * a.dx + a.dy * a.dy, b2 = b.dx * b.dx + b.dy * b.dy;
    if (!(den > 0.0 && den * den > 1e-24 * a2 * b2)) return false;
    const double rx = a.ax - b.ax, ry = a.ay - b.ay;
    const double sb = a.dx * ry - a.dy * rx, sa = b.dx * ry - b.dy * rx;
    const double limit = edges.tol2 * den * den;
    // Each end decides through the nearer one (x·x·c, rounded, does not decrease with x > 0).
    const double mb = std::min(sb, den - sb), ma = std::min(sa, den - sa);
    ok &= (mb > 0.0) & (ma > 0.0) & (mb * mb * b2 > limit) & (ma * ma * a2 > limit);
    const double t = sb / den;
    v[k] = Vec2(b.ax + t * b.dx, b.ay + t * b.dy);
  }
  if (switches != 2 || !ok) return false;
  for (std::size_t k = 0; k < K; ++k) {
    const Vec2 e = v[k + 1 == K ? 0 : k + 1] - v[k];
    ok &= (e.x() * line[k].dx + e.y() * line[k].dy > 0.0) & (e.squaredNorm() > edges.tol2);
  }
  if (K >= 5) {
    // Every turn is to the left by less than π (the crossings' den > 0; the corners of convex polygons), so the
    // direction of the edges winds once, and the polygon is convex, when it passes +x once: dy going from below
    // 0 to 0 or above (exact signs of the lines' directions; a corner bent backwards by round-off at most adds
    // a pass, which refuses the polygon).
    int passes = 0;
    for (std::size_t k = 0; k < K; ++k) passes += (line[k == 0 ? K - 1 : k - 1].dy < 0.0) & (line[k].dy >= 0.0);
    ok &= passes == 1;
  }
  return ok;
}

// The contact geometry of a regular overlap polygon from its lines and vertices (local frame about o).
ContactGeometry regular_contact(const PairEdges& edges, const int* label, const Vec2* v, std::size_t K, const Vec2& o,
                                const Vec2& dc, double eps_area) {
  ContactGeometry r;
  double twice = 0.0;
  for (std::size_t k = 1; k + 1 < K; ++k) twice += cross(v[k] - v[0], v[k + 1] - v[0]);
  const double area = 0.5 * twice;
  if (!(area > eps_area)) return r;
  std::array<Vec2, 2> crossing;
  std::size_t count = 0;
  for (std::size_t k = 0; k < K; ++k) {
    if (edges.of_j(label[k == 0 ? K - 1 : k - 1]) != edges.of_j(label[k])) crossing[count++] = v[k];
  }
  r.kind = ContactGeometry::Kind::line;
  r.area = area;
  r.crossings = r.distinct_crossings = 2;
  r.p1 = crossing[0] + o;
  r.p2 = crossing[1] + o;
  r.point = 0.5 * (crossing[0] + crossing[1]) + o;
  r.normal = line_normal(crossing[0], crossing[1], dc);
  return r;
}

}  // namespace frac::geometry::detail
