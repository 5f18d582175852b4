#pragma once
// Validation of meshes: the invariants every tool may rely on, and a short summary for people.
#include <map>
#include <string>
#include <vector>

#include "mesh/cell_mesh.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::mesh {

struct MeshReport {
  std::vector<std::string> failures;            // one line per failed invariant (empty: valid)
  std::map<int, std::int64_t> neighbour_count;  // beams (or intact bonds) per cell/node -> how many
  std::string summary;                          // a few human-readable lines
  bool ok() const { return failures.empty(); }
};

// Cells: at least one; vertex offsets increasing, >= 3 vertices each; every polygon convex and
// counter-clockwise with its centroid at the body origin; area and second moment consistent with the
// vertices; beams unique, a < b, in range, l0 = centroid distance, section > 0 and equal to the length
// of the side the two cells share; no two cells overlap (they meet along sides; mesh/cell_overlaps).
MeshReport check_cell_mesh(const CellMesh& m);

// Nodes: at least two; positions finite; bonds unique, a < b, in range, lengths = distances.
MeshReport check_node_mesh(const NodeMesh& m);

}  // namespace frac::mesh
