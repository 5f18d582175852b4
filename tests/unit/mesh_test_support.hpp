#pragma once
// What several unit tests of the mesh layer and above share: small meshes.
#include "mesh/node_mesh.hpp"

namespace frac::test {

// Two nodes 1 m apart joined by one intact bond (a 2 × 1 lattice).
inline mesh::NodeMesh two_node_mesh() {
  mesh::NodeMesh m;
  m.position = {mesh::Vec2(0, 0), mesh::Vec2(1, 0)};
  m.bond = {{0, 1}};
  m.bond_length = {1.0};
  m.intact = {1};
  m.nx = 2, m.ny = 1, m.spacing = 1.0;
  return m;
}

}  // namespace frac::test
