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

mesh::CellMesh read_cell_mesh(const Group& root);
mesh::NodeMesh read_node_mesh(const Group& root);

}  // namespace frac::io
