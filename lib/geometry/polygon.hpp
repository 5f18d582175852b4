#pragma once
// Properties of simple polygons given as vertex lists (counter-clockwise for positive area),
// and clipping of a polygon by a convex one. Units follow the input (metres in the toolkit).
#include <span>
#include <vector>

#include "geometry/vec2.hpp"

namespace frac::geometry {

using Polygon = std::vector<Vec2>;

// Signed area by the shoelace formula: positive for counter-clockwise vertices. 0 for fewer than 3.
double signed_area(std::span<const Vec2> poly);

// Area centroid. For a degenerate polygon (|area| below 1e-300 or fewer than 3 vertices) the mean
// of the vertices (the origin for an empty list).
Vec2 centroid(std::span<const Vec2> poly);

// Polar second moment of area about the centroid, J_c = integral of |r - c|^2 dA (m^4), from
// J_O = (1/12) sum (x_k y_k+1 - x_k+1 y_k)(x_k^2 + x_k x_k+1 + x_k+1^2 + y_k^2 + y_k y_k+1 + y_k+1^2)
// and J_c = J_O - A |c|^2, evaluated about the first vertex to avoid cancellation. Signed like
// signed_area: negative for clockwise vertices.
double polar_second_moment(std::span<const Vec2> poly);

// Diameter of the disc of the same area, r = 2 sqrt(A / pi): the paper's length for the contact law.
double equal_area_diameter(double area);

// True if the polygon has at least 3 vertices, positive area, makes no right turn beyond
// tolerance (cross(e_k, e_k+1) >= -tol * |e_k| |e_k+1| for consecutive edges) and turns once
// around (a star such as the pentagram, all left turns but twice around, is rejected). Repeated
// and collinear vertices are accepted.
bool is_convex_ccw(std::span<const Vec2> poly, double tol = 1e-12);

// Intersection of `subject` with the half-plane on the left of the directed line a->b
// (Sutherland-Hodgman step). Points within `tol` (distance) of the line count as inside: the
// half-plane is widened by `tol` and crossings lie on its widened border. A vertex exactly on the
// border is not repeated as a crossing.
Polygon clip_half_plane(std::span<const Vec2> subject, const Vec2& a, const Vec2& b, double tol = 0.0);

// Intersection of `subject` (any simple polygon, counter-clockwise) with the convex
// counter-clockwise polygon `clip`, by Sutherland-Hodgman. Consecutive duplicate vertices (closer
// than `merge_tol`) are merged. Empty when they do not overlap.
Polygon clip_convex(std::span<const Vec2> subject, std::span<const Vec2> clip, double merge_tol = 0.0);

// Remove consecutive vertices closer than tol (including last-first) and vertices collinear with
// their neighbours within tol (distance of the middle vertex from the chord).
Polygon simplify(std::span<const Vec2> poly, double tol);

}  // namespace frac::geometry
