#pragma once
// Cells of a valid mesh meet along sides only. This finds the pairs that overlap (a cell stacked on another,
// a copied or shifted cell) in time linear in the cells: candidate pairs come from a grid of buckets by
// centroid, and a pair is tested by its separating edges (geometry/separation) before its overlap is measured.
#include <cstddef>
#include <vector>

#include "mesh/cell_mesh.hpp"

namespace frac::mesh {

struct CellOverlap {
  std::size_t a, b;  // cells, a < b
  double area;       // m^2 of their intersection (NaN for a polygon above geometry's vertex limit)
};

struct OverlapSearch {
  std::vector<CellOverlap> found;  // at most `most`, in order of the first cell
  std::size_t pairs = 0;           // candidate pairs looked at
  // false: cells so unequal in size that looking at every pair within reach would take more than linear time;
  // `widest` is then a cell reaching farthest from its centroid.
  bool complete = true;
  std::size_t widest = 0;
};

// Pairs of cells (finite, convex counter-clockwise) that no edge of either separates with a penetration of more
// than `slack` (m); `length_scale` g > 0 sets geometry's area tolerance. Stops after `most` pairs.
OverlapSearch find_cell_overlaps(const CellMesh& m, double slack, double length_scale, std::size_t most);

}  // namespace frac::mesh
