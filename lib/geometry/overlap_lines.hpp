#pragma once
// The regular overlap of two convex polygons, computed from the lines that bound it (convex_overlap's fast path,
// geometry/overlap.hpp): what the cached lines of a pair and the clipper's result share. Internal to
// geometry/overlap.cpp.
#include <array>
#include <cstddef>
#include <span>
#include <tuple>

#include "geometry/overlap.hpp"
#include "geometry/vec2.hpp"

namespace frac::geometry::detail {

// n perpendicular to the contact line (p2 - p1 != 0), oriented from i toward j. (The orientation from the
// unscaled perpendicular, so that it does not wait for the square root and the division; lengths ≥ eps_L ~
// 1e-11 m: no under/overflow.)
Vec2 line_normal(const Vec2& p1, const Vec2& p2, const Vec2& dc);

// The edges of both polygons as lines in the local frame about o, by label (0..n-1 the edges of P_i, n + b
// edge b of P_j): first vertex (ax, ay) and direction d = p_{k+1} − p_k, computed when asked for.
struct PairEdges {
  std::span<const Vec2> pi, pj;
  double ox, oy;
  int n, m;
  double tol, tol2;  // the margin of a regular overlap, and its square
  struct Line {
    double ax, ay, dx, dy;
  };
  bool of_j(int l) const { return l >= n; }
  int next(int l) const { return l < n ? (l + 1 == n ? 0 : l + 1) : (l + 1 == n + m ? n : l + 1); }
  // The line from a to b (world vertices), in the local frame.
  Line through(const Vec2& a, const Vec2& b) const {
    const double ax = a.x() - ox, ay = a.y() - oy;
    return {ax, ay, (b.x() - ox) - ax, (b.y() - oy) - ay};
  }
  Line line(int l) const {
    const bool j = l >= n;
    const std::span<const Vec2> p = j ? pj : pi;
    const auto k = static_cast<std::size_t>(j ? l - n : l);
    return through(p[k], p[k + 1 == p.size() ? 0 : k + 1]);
  }
  // A facing edge of each polygon (P_i's first) whose reach leaves room for the margin: within the reach of
  // its midpoint, every line of that polygon but the edge's own and its two neighbours' is more than
  // 1e-3 reach > tol away (edge_reach), so those three lines decide.
  struct Near {
    int edge = -1;  // none
    double mx = 0, my = 0, reach2 = 0;
  };
  std::array<Near, 2> near;
  void set_near(bool j, std::size_t edge, double reach) {
    const std::span<const Vec2> p = j ? pj : pi;
    if (edge >= p.size() || !(reach > 1e3 * tol)) return;
    const Vec2& a = p[edge];
    const Vec2& b = p[edge + 1 == p.size() ? 0 : edge + 1];
    near[j] = {static_cast<int>(edge) + (j ? n : 0), 0.5 * ((a.x() - ox) + (b.x() - ox)),
               0.5 * ((a.y() - oy) + (b.y() - oy)), reach * reach};
  }
  // (x, y) more than tol inside the line.
  static bool inside(double x, double y, const Line& l, double tol2) {
    const double s = l.dx * (y - l.ay) - l.dy * (x - l.ax);
    return (s > 0.0) & (s * s > tol2 * (l.dx * l.dx + l.dy * l.dy));
  }
  // (x, y) more than tol inside every edge line of P_j (j) or of P_i.
  bool inside_polygon(double x, double y, bool j) const {
    const Near& f = near[j];
    if (f.edge >= 0 && (x - f.mx) * (x - f.mx) + (y - f.my) * (y - f.my) <= f.reach2) {
      // The lines of edges e−1, e, e+1, through their four vertices.
      const std::span<const Vec2> p = j ? pj : pi;
      const std::size_t size = p.size(), e = static_cast<std::size_t>(f.edge - (j ? n : 0));
      const std::size_t e0 = e == 0 ? size - 1 : e - 1, e2 = e + 1 == size ? 0 : e + 1;
      const std::size_t e3 = e2 + 1 == size ? 0 : e2 + 1;
      return inside(x, y, through(p[e0], p[e]), tol2) & inside(x, y, through(p[e], p[e2]), tol2) &
             inside(x, y, through(p[e2], p[e3]), tol2);
    }
    const std::span<const Vec2> p = j ? pj : pi;
    double ax = p.back().x() - ox, ay = p.back().y() - oy;
    bool ok = true;
    for (const Vec2& q : p) {
      const double bx = q.x() - ox, by = q.y() - oy;
      const double dx = bx - ax, dy = by - ay;
      const double s = dx * (y - ay) - dy * (x - ax);
      ok &= (s > 0.0) & (s * s > tol2 * (dx * dx + dy * dy));
      ax = bx;
      ay = by;
    }
    return ok;
  }
};

// Most vertices of an overlap polygon computed from its lines (beyond: clipping's conventions).
constexpr std::size_t kMaxRegularVertices = std::tuple_size_v<decltype(OverlapLines::label)>;

// The vertices of the polygon bounded by the lines `label` [0, K) in order (edge k on line label[k], vertex k
// = line label[k−1] ∩ line label[k]; a corner of one polygon is that vertex itself) into v, when the polygon
// is regular (convex_overlap): false otherwise. Every turn is to the left, every edge runs along its line and
// is longer than tol, a crossing lies on both its edges more than tol from their ends, a corner of one
// polygon more than tol inside every edge line of the other. Such a polygon (convex: checked for five
// vertices or more, where turns to the left could wind twice) is P_i ∩ P_j: its vertices lie in both, and it
// is the intersection of the half-planes of its own edges, each of which contains P_i ∩ P_j.
bool regular_vertices(const PairEdges& edges, const int* label, std::size_t K, Vec2* v);

// The contact geometry of a regular overlap polygon from its lines and vertices (local frame about o).
ContactGeometry regular_contact(const PairEdges& edges, const int* label, const Vec2* v, std::size_t K, const Vec2& o,
                                const Vec2& dc, double eps_area);

// What both paths of convex_overlap share: the local frame about o = P_i's first vertex (the differences of
// nearby coordinates are exact, so the result does not depend on the distance from the origin), the pair's
// edges in it, the tolerances, and where a regular overlap's lines and vertices go.
struct OverlapFrame {
  OverlapFrame(const PairEdges& e, const Vec2& origin, const Vec2& centres, double area_tol, double len_tol,
               OverlapPolygon* polygon)
      : edges(e), o(origin), dc(centres), eps_area(area_tol), eps_len(len_tol), overlap(polygon) {}
  PairEdges edges;
  Vec2 o, dc;
  double eps_area, eps_len;
  OverlapPolygon* overlap;
  std::array<int, kMaxRegularVertices> label;  // (filled before use)
  std::array<Vec2, kMaxRegularVertices> v;
  // The result of the regular overlap in label/v [0, K).
  ContactGeometry regular_result(std::size_t K) {
    if (overlap) {
      overlap->size = K;
      for (std::size_t k = 0; k < K; ++k) overlap->vertex[k] = v[k] + o;
    }
    return regular_contact(edges, label.data(), v.data(), K, o, dc, eps_area);
  }
};

}  // namespace frac::geometry::detail
