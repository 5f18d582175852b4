#include "render/figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace frac::render {

std::vector<Vec2> world_polygon(std::span<const Vec2> body, const Vec2& position, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> out;
  out.reserve(body.size());
  for (const auto& v : body)
    out.emplace_back(position.x() + c * v.x() - s * v.y(), position.y() + s * v.x() + c * v.y());
  return out;
}

std::array<double, 4> content_bounds(const Figure& f, double margin) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 4> b{inf, inf, -inf, -inf};
  auto add = [&](const Vec2& p, double r) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
    b[0] = std::min(b[0], p.x() - r);
    b[1] = std::min(b[1], p.y() - r);
    b[2] = std::max(b[2], p.x() + r);
    b[3] = std::max(b[3], p.y() + r);
  };
  for (const auto& p : f.polygons)
    for (const auto& v : p.vertex) add(v, 0.0);
  for (const auto& d : f.dots) add(d.at, f.dot_radius);
  for (const auto& s : f.segments) {
    add(s.a, 0.0);
    add(s.b, 0.0);
  }
  if (!(b[2] >= b[0])) return {0, 0, 1, 1};
  // A degenerate box (one point, a line) gets the link length or a unit extent.
  const double pad = std::max(f.link_length, 1e-12);
  if (b[2] - b[0] <= 0) b[0] -= pad, b[2] += pad;
  if (b[3] - b[1] <= 0) b[1] -= pad, b[3] += pad;
  const double m = margin * std::max(b[2] - b[0], b[3] - b[1]);
  return {b[0] - m, b[1] - m, b[2] + m, b[3] + m};
}

std::array<double, 4> merge_bounds(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  return {std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[2], b[2]), std::max(a[3], b[3])};
}

}  // namespace frac::render
