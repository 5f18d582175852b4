#pragma once
// The mesh part of the file layout (docs/SCHEMA.md): /particles/cells + /connectivity/beams for the
// polygon DEM, /particles/nodes + /connectivity/bonds for the rubber lattice. Written and read here
// only; every reader checks shapes and names the dataset at fault.
#include "io/hdf5.hpp"
#include "mesh/cell_mesh.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::io {

void write_mesh(Group& root, const mesh::CellMesh& m);
void write_mesh(Group& root, const mesh::NodeMesh& m);

enum class MeshKind { cells, nodes };
// Which mesh a file holds; InputError naming the file when it holds none.
MeshKind mesh_kind(const Group& root);

// Every reader of a mesh (also a run's) gets it through these: shapes checked, then the invariants of
// mesh/check (those of mesh-gen check); InputError naming the file and the first cells, beams or nodes at
// fault.
mesh::CellMesh read_cell_mesh(const Group& root);
mesh::NodeMesh read_node_mesh(const Group& root);
// Shapes only, for mesh-gen check, which reports every invariant itself.
mesh::CellMesh read_cell_mesh_as_stored(const Group& root);
mesh::NodeMesh read_node_mesh_as_stored(const Group& root);

}  // namespace frac::io
