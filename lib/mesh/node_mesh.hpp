#pragma once
// Mass points on a triangular lattice joined by nearest-neighbour bonds: the reference state of the
// rubber lattice. Struct of arrays; lengths in metres. Written and read by io/mesh_io.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/vec2.hpp"

namespace frac::mesh {

using geometry::Vec2;

struct NodeMesh {
  std::vector<Vec2> position;  // m, reference positions, row-major: index = row * nx + column
  // Nearest-neighbour bonds, node_a < node_b, sorted. A bond cut by the notch stays in the list with
  // intact = 0, so the reference neighbour lists stay complete and the cut is visible.
  std::vector<std::array<std::int64_t, 2>> bond;
  std::vector<double> bond_length;   // m, reference length (= spacing)
  std::vector<std::uint8_t> intact;  // 1 intact, 0 cut

  std::int64_t nx = 0, ny = 0;   // nodes along x and along y
  double spacing = 0.0;          // m, lattice spacing (Delta)
  std::string rows_along = "x";  // close-packed rows along "x" or "y"
  double notch_length = 0.0;     // m, length of the cut measured from the left edge (0: none)
  double notch_y = 0.0;          // m, height of the line the notch cuts along

  std::size_t nodes() const { return position.size(); }
  std::size_t bonds() const { return bond.size(); }
};

}  // namespace frac::mesh
