#include "geometry/separation.hpp"

#include <limits>

namespace frac::geometry {

std::size_t facing_edge(std::span<const Vec2> p, const Vec2& d) {
  // The facing edge is one of the two edges at p's support vertex in direction d.
  const std::size_t n = p.size();
  std::size_t s = 0;
  double best = p[0].dot(d);
  for (std::size_t a = 1; a < n; ++a) {
    const double h = p[a].dot(d);
    if (h > best) {
      best = h;
      s = a;
    }
  }
  const std::size_t prev = s == 0 ? n - 1 : s - 1;
  const Vec2 e_out = p[s + 1 == n ? 0 : s + 1] - p[s];  // edge s -> s+1
  const Vec2 e_in = p[s] - p[prev];                     // edge s-1 -> s
  const double l_out = e_out.norm(), l_in = e_in.norm();
  // Outward normal of edge e (counter-clockwise polygon): (e_y, −e_x)/|e|.
  const double f_out = l_out > 0 ? (e_out.y() * d.x() - e_out.x() * d.y()) / l_out : -1e300;
  const double f_in = l_in > 0 ? (e_in.y() * d.x() - e_in.x() * d.y()) / l_in : -1e300;
  return f_out >= f_in ? s : prev;
}

bool edge_separates(std::span<const Vec2> p, std::size_t edge, std::span<const Vec2> q, double slack) {
  const detail::SeparatingEdge line(p, edge, slack);
  if (!line.valid) return false;
  // Branch-free: a separated pair, the usual case, has every vertex to test anyway.
  double deepest = 0.0;
  for (const Vec2& v : q) deepest = std::min(deepest, line.clearance(v));
  return line.separates(deepest);
}

bool detail::separates_from_all(const SeparatingEdge& line, std::span<const Vec2> q, std::uint8_t& deepest_vertex) {
  double deepest = 0.0, lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < q.size(); ++k) {
    const double d = line.clearance(q[k]);
    deepest = std::min(deepest, d);
    if (d < lowest) {
      lowest = d;
      deepest_vertex = static_cast<std::uint8_t>(k);
    }
  }
  return line.separates(deepest);
}

}  // namespace frac::geometry
