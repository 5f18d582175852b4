#pragma once
// Voronoi cells of a set of sites, clipped to a box. The only interface to CGAL: its
// implementation (voronoi.cpp) is the one translation unit of the project that includes CGAL.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/polygon.hpp"

namespace frac::mesh {

struct VoronoiDiagram {
  // cell[k]: Voronoi cell of site k clipped to the box, counter-clockwise, near-duplicate vertices
  // merged. Empty if the site lies outside the box.
  std::vector<geometry::Polygon> cell;
  // Pairs of sites (a < b) whose clipped cells share a side, and that side's length in m (> 0).
  std::vector<std::array<std::int64_t, 2>> neighbour;
  std::vector<double> shared_side;
};

// box = {xmin, ymin, xmax, ymax}. Sites must be distinct. `merge_tol` (m) merges cell vertices
// closer than that (the 4-fold vertices of a square grid) and drops sides shorter than it.
VoronoiDiagram voronoi_in_box(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box,
                              double merge_tol);

}  // namespace frac::mesh
