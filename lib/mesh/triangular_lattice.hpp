#pragma once
// Triangular lattice of nx x ny nodes at spacing Delta, nearest-neighbour bonds, with close-packed
// rows along x (rows at height j * Delta sqrt(3)/2, odd rows shifted by Delta/2) or along y (the same
// lattice turned by 90 degrees), and an optional notch: the bonds crossing the middle horizontal line
// between the two middle node levels, from the left edge over a given length, are cut.
#include <cstdint>
#include <string>

#include "mesh/node_mesh.hpp"

namespace frac::mesh {

struct TriangularLatticeOptions {
  std::int64_t nx = 0, ny = 0;   // nodes along x and along y
  double spacing = 0.0;          // m
  std::string rows_along = "x";  // "x" or "y"
  double notch = 0.0;            // m, 0 for no notch
};

// Throws UsageError (naming the option) for invalid options.
NodeMesh make_triangular_lattice(const TriangularLatticeOptions& opt);

}  // namespace frac::mesh
