#pragma once
// The neighbour structure of the rubber lattice, built once from a triangular node mesh.
//
// Every node has six slots s = 0..5, the directions base + 60°·s in the reference lattice (base = 0°
// for close-packed rows along x, 30° for rows along y). Slots 0, 1, 2 are the node's forward bonds:
// bond id 3i + s. Slot s + 3 of node i is the forward bond s of the neighbour j = nbr(i, s + 3), seen
// from the other end. A slot without a neighbour (free edge) points to the sentinel node n, whose
// bonds and forces are kept zero; so the force loops run over six slots everywhere without branches.
// Bonds the mesh marks cut (the notch) exist but start not intact.
//
// Periodic boundaries add the wrap-around bonds the mesh lacks, with the image shift of the box
// (reference frame, m); they have no index in the mesh's bond list.
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/node_mesh.hpp"

namespace frac::rubber {

struct Lattice {
  std::size_t n = 0;                  // nodes; index n is the sentinel "no neighbour"
  double spacing = 0;                 // Δ (m)
  double base_angle = 0;              // rad: direction of slot 0 (0 or π/6)
  std::array<double, 12> slot_dir{};  // reference unit vectors of the six slots (x0, y0, x1, ...)
  std::int64_t nx = 0, ny = 0;
  bool rows_along_x = true;
  bool periodic_x = false, periodic_y = false;
  double box_x = 0, box_y = 0;  // m: reference periods (0 when not periodic)

  std::vector<double> rx, ry;           // [n] reference positions (m)
  std::vector<std::int32_t> nbr;        // [6(n+1)] neighbour in slot s, or n
  std::vector<std::uint8_t> exists;     // [3(n+1)] forward bond exists (mesh or wrap bond)
  std::vector<std::uint8_t> intact;     // [3(n+1)] exists and not cut in the mesh
  std::vector<std::int64_t> mesh_bond;  // [3(n+1)] index in the mesh's bond list; -1 for wrap or none
  std::vector<std::int64_t> bond_id;    // [mesh bonds] forward bond id 3i + s of mesh bond k
  std::vector<double> shift;            // [2·3(n+1)] reference image shift of a wrap bond (else 0)

  std::size_t bonds() const { return 3 * (n + 1); }  // forward bond slots, sentinel included
  std::int32_t neighbour(std::size_t i, int s) const { return nbr[6 * i + static_cast<std::size_t>(s)]; }
  // The two nodes of forward bond b (the second is n when the bond does not exist).
  std::size_t bond_node(std::size_t b) const { return b / 3; }
  std::size_t bond_other(std::size_t b) const { return static_cast<std::size_t>(nbr[6 * (b / 3) + b % 3]); }
};

// InputError when the mesh is not a triangular lattice of nearest-neighbour bonds (naming the bond);
// UsageError when a periodic direction does not fit the lattice (odd number of rows, too few nodes).
Lattice build_lattice(const mesh::NodeMesh& mesh, bool periodic_x = false, bool periodic_y = false);

}  // namespace frac::rubber
