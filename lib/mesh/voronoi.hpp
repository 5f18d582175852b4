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

// box = {xmin, ymin, xmax, ymax}. Sites must be distinct (std::invalid_argument otherwise). All sites
// take part in the tessellation; cells and pairs are reported only for sites inside the box.
// `merge_tol` (m) merges Voronoi vertices closer than that (the 4-fold vertices of a square grid):
// once for all cells, so neighbouring cells keep identical shared vertices and the cells tile the box
// to round-off. Sides not longer than it are not reported as shared. Output is deterministic: cells
// start at their lowest (then leftmost) vertex, pairs are sorted.
VoronoiDiagram voronoi_in_box(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box,
                              double merge_tol);

// The same diagram with the cells in one flat array (no allocation per cell): cell k has vertices
// vertex[offset[k] .. offset[k+1]) (none if its site lies outside the box); offset has size sites + 1.
struct FlatVoronoiDiagram {
  std::vector<std::int64_t> offset;
  std::vector<geometry::Vec2> vertex;
  std::vector<std::array<std::int64_t, 2>> neighbour;
  std::vector<double> shared_side;
};
FlatVoronoiDiagram voronoi_in_box_flat(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box,
                                       double merge_tol);

}  // namespace frac::mesh
