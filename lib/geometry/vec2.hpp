#pragma once
// 2D vectors: Eigen's fixed-size Vector2d plus the scalar cross product of the plane.
#include <Eigen/Core>

namespace frac::geometry {

using Vec2 = Eigen::Vector2d;

// z component of a x b.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
// z x a: a turned by +90 degrees.
inline Vec2 perp(const Vec2& a) { return Vec2(-a.y(), a.x()); }

}  // namespace frac::geometry
