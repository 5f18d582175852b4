#include "geometry/polygon.hpp"

#include <cmath>
#include <numbers>

namespace frac::geometry {

double signed_area(std::span<const Vec2> poly) {
  const std::size_t n = poly.size();
  if (n < 3) return 0.0;
  // About the first vertex: exact for translated polygons far from the origin.
  const Vec2 o = poly[0];
  double twice = 0.0;
  for (std::size_t k = 1; k + 1 < n; ++k) twice += cross(poly[k] - o, poly[k + 1] - o);
  return 0.5 * twice;
}

Vec2 centroid(std::span<const Vec2> poly) {
  const std::size_t n = poly.size();
  if (n == 0) return Vec2::Zero();
  const Vec2 o = poly[0];
  double twice = 0.0;
  Vec2 moment = Vec2::Zero();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const Vec2 a = poly[k] - o, b = poly[k + 1] - o;
    const double w = cross(a, b);
    twice += w;
    moment += w * (a + b);
  }
  if (n < 3 || std::abs(twice) < 1e-300) {
    Vec2 mean = Vec2::Zero();
    for (const auto& p : poly) mean += p;
    return mean / static_cast<double>(n);
  }
  return o + moment / (3.0 * twice);
}

double polar_second_moment(std::span<const Vec2> poly) {
  const std::size_t n = poly.size();
  if (n < 3) return 0.0;
  const Vec2 o = poly[0];
  double area2 = 0.0, j = 0.0;
  Vec2 moment = Vec2::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = poly[k] - o, b = poly[(k + 1) % n] - o;
    const double w = cross(a, b);
    area2 += w;
    moment += w * (a + b);
    j += w * (a.squaredNorm() + a.dot(b) + b.squaredNorm());
  }
  const double area = 0.5 * area2;
  if (std::abs(area) < 1e-300) return 0.0;
  const Vec2 c = moment / (3.0 * area2);  // centroid relative to o
  return j / 12.0 - area * c.squaredNorm();
}

double equal_area_diameter(double area) { return 2.0 * std::sqrt(area / std::numbers::pi); }

bool is_convex_ccw(std::span<const Vec2> poly, double tol) {
  const std::size_t n = poly.size();
  if (n < 3 || signed_area(poly) <= 0.0) return false;
  // No right turn beyond tolerance, and the edge direction turns once around in total: a
  // self-intersecting star (the pentagram 0-2-4-1-3) has only left turns and positive area, but
  // turns twice around (4 pi).
  double turning = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 e1 = poly[(k + 1) % n] - poly[k];
    const Vec2 e2 = poly[(k + 2) % n] - poly[(k + 1) % n];
    const double c = cross(e1, e2);
    if (c < -tol * e1.norm() * e2.norm()) return false;
    turning += std::atan2(c, e1.dot(e2));
  }
  // A closed polygon turns by a multiple of 2 pi; accept only once around.
  return std::abs(turning - 2.0 * std::numbers::pi) < std::numbers::pi;
}

Polygon clip_half_plane(std::span<const Vec2> subject, const Vec2& a, const Vec2& b, double tol) {
  Polygon out;
  const std::size_t n = subject.size();
  if (n == 0) return out;
  out.reserve(n + 2);
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len == 0.0) return Polygon(subject.begin(), subject.end());
  // Distance inside the widened half-plane s >= -tol, where s is the signed distance from the line
  // (positive on the left). Crossings are placed on its border s = -tol, so that the result is the
  // exact intersection with that half-plane (a crossing at s = 0 would lie outside the segment pq
  // when p is inside only by tolerance).
  auto inside = [&](const Vec2& p) { return cross(d, p - a) / len + tol; };
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& p = subject[k];
    const Vec2& q = subject[(k + 1) % n];
    const double sp = inside(p), sq = inside(q);
    const bool pin = sp >= 0.0, qin = sq >= 0.0;
    if (pin) out.push_back(p);
    // A crossing strictly between p and q. When the inside end lies exactly on the border the
    // crossing is that end itself, already in the output (or about to be): do not duplicate it.
    if (pin && !qin && sp > 0.0) out.push_back(p + (sp / (sp - sq)) * (q - p));
    if (!pin && qin && sq > 0.0) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

Polygon clip_convex(std::span<const Vec2> subject, std::span<const Vec2> clip, double merge_tol) {
  Polygon result(subject.begin(), subject.end());
  const std::size_t m = clip.size();
  for (std::size_t k = 0; k < m && !result.empty(); ++k) {
    result = clip_half_plane(result, clip[k], clip[(k + 1) % m]);
  }
  if (merge_tol > 0.0) result = simplify(result, merge_tol);
  if (result.size() < 3) result.clear();
  return result;
}

Polygon simplify(std::span<const Vec2> poly, double tol) {
  Polygon out;
  out.reserve(poly.size());
  for (const auto& p : poly) {
    if (out.empty() || (p - out.back()).norm() > tol) out.push_back(p);
  }
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tol) out.pop_back();
  // Drop vertices lying on the chord of their neighbours (repeat until nothing changes).
  bool changed = true;
  while (changed && out.size() >= 3) {
    changed = false;
    for (std::size_t k = 0; k < out.size() && out.size() >= 3; ++k) {
      const Vec2& prev = out[(k + out.size() - 1) % out.size()];
      const Vec2& next = out[(k + 1) % out.size()];
      const Vec2 chord = next - prev;
      const double len = chord.norm();
      const double dist = len > 0.0 ? std::abs(cross(chord, out[k] - prev)) / len : (out[k] - prev).norm();
      if (dist <= tol) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
        break;
      }
    }
  }
  return out;
}

}  // namespace frac::geometry
