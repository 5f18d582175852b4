#pragma once
// Separating-edge tests between convex polygons: the cheap rejection that comes before their overlap
// (geometry/overlap.hpp), for the pairs of a neighbour list.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "geometry/vec2.hpp"

namespace frac::geometry {

// A cheap test that comes before convex_overlap: the edge of p (index of its first vertex) whose
// outward normal points most along d (toward the other polygon), and whether edge `edge` of p
// separates q from p, allowing a penetration of at most `slack`. With slack ≤ eps_A / (the polygons'
// diameter), every pair it reports separated is one convex_overlap reports as none, so skipping those
// pairs changes no result. Neighbours of an unstressed tessellation touch along a shared edge and are
// separated by it. A neighbour list caches the separating edges of each pair and tests them first.
std::size_t facing_edge(std::span<const Vec2> p, const Vec2& d);
bool edge_separates(std::span<const Vec2> p, std::size_t edge, std::span<const Vec2> q, double slack);
// The same, with a hint kept by the caller: `deepest_vertex`, the vertex of q that lay deepest along the edge's
// normal at the last test (updated when another does). When it is still no deeper than its two neighbours it is
// the deepest, on a convex q, and only those three are tested. (On a q that round-off made not quite convex the
// answer may differ from the full test's by round-off, within the slack's margin: a pair it calls separated
// still has an overlap area below eps_A.)
inline bool edge_separates(std::span<const Vec2> p, std::size_t edge, std::span<const Vec2> q, double slack,
                           std::uint8_t& deepest_vertex);

namespace detail {
// Edge `edge` of p as edge_separates tests it. clearance(v) = −e × (v − a) is the distance of v outside the
// edge's line (p's inside is on its left) times |e|: negative for a vertex that has crossed into p, and a
// penetration of more than `slack` shows as clearance < 0 with clearance² > limit2 (compared squared, no sqrt).
struct SeparatingEdge {
  Vec2 a, w;  // first vertex; (e.y, e.x), both products of the cross product in one vector multiply
  double limit2;
  bool valid;
  SeparatingEdge(std::span<const Vec2> p, std::size_t edge, double slack) {
    const std::size_t n = p.size();
    valid = edge < n;
    if (!valid) return;
    a = p[edge];
    const Vec2 e = p[edge + 1 == n ? 0 : edge + 1] - a;
    const double e2 = e.squaredNorm();
    valid = e2 > 0;
    w = Vec2(e.y(), e.x());
    limit2 = slack * slack * e2;
  }
  double clearance(const Vec2& v) const {
    const Vec2 t = (v - a).cwiseProduct(w);
    return t.x() - t.y();
  }
  // The deepest vertex decides (the square grows as the clearance falls below 0); NaN clearances do not count.
  bool separates(double deepest) const { return !(deepest < 0 && deepest * deepest > limit2); }
};
// The test over every vertex of q, which also finds the deepest.
bool separates_from_all(const SeparatingEdge& line, std::span<const Vec2> q, std::uint8_t& deepest_vertex);
}  // namespace detail

// (Inline: the contact search calls it for most neighbour pairs, in its innermost loop.)
inline bool edge_separates(std::span<const Vec2> p, std::size_t edge, std::span<const Vec2> q, double slack,
                           std::uint8_t& deepest_vertex) {
  const detail::SeparatingEdge line(p, edge, slack);
  if (!line.valid) return false;
  const std::size_t m = q.size();
  if (m == 0) return true;
  // The clearance is linear along the edge's normal, so on a convex q a vertex no deeper than its two neighbours
  // is the deepest: then they are the only other vertices to test.
  const std::size_t s = deepest_vertex < m ? deepest_vertex : 0;
  const double here = line.clearance(q[s]);
  if (here <= line.clearance(q[s == 0 ? m - 1 : s - 1]) && here <= line.clearance(q[s + 1 == m ? 0 : s + 1])) {
    deepest_vertex = static_cast<std::uint8_t>(s);
    return line.separates(std::min(0.0, here));
  }
  return detail::separates_from_all(line, q, deepest_vertex);
}

}  // namespace frac::geometry
