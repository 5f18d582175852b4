#pragma once
// Contacts between cells (physics/polygon-dem.md §3): neighbour search on a cell list with cells of
// the largest polygon diameter, pairs culled by bounding circles before any clipping, the overlap
// geometry of each candidate pair (geometry/overlap), and the three contact force terms, each a
// separate loop over the contact list that the engine calls only when the scene turns it on:
//   contact_elastic   F_n = −Y·A·h/L_c along n, at the contact line's midpoint R
//   contact_damping   + m_eff·γ_N·v_n along n (v_n < 0 while approaching)
//   contact_friction  F_t = sign(v_t)·min(m_eff·γ_T·|v_t|, μ·|F_n|) along t = ẑ × n
// Every pair force is equal and opposite and acts at one point, so momentum and angular momentum are
// conserved exactly. Each term returns the power it delivers to the bodies (W) for the energy ledger, and
// adds its force to each contact's slot; one pass (add_contact_forces) then adds the contacts' forces, summed
// over the terms, to the cells.
// Threads (OpenMP) share the neighbour-list rebuild (contiguous ranges of cells, joined in order), the
// neighbour pairs (circle test, separating edges, overlap geometry; each thread its cells' pairs first) and
// the contact forces, each written to its own slot; the list is then filled in pair order (each thread its
// block of pairs, at offsets from the counts of the blocks before it), and the contacts' forces are added to
// the cells in contact order, so results do not depend on the thread count. The overlap of a
// pair gets a hint (geometry::OverlapHint): the cached facing edges and their reaches, precomputed per cell
// edge, which leave out clip lines that cannot cut.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.hpp"
#include "dem/bodies.hpp"
#include "geometry/overlap.hpp"
#include "geometry/vec2.hpp"

namespace frac::dem {

using geometry::Vec2;

// The force on i of one contact (j receives −F), summed over the contact force terms that ran, N.
struct PairForce {
  double fx, fy;
};

struct ContactList {
  std::vector<std::int32_t> i, j;
  std::vector<double> rx, ry;   // application point R, m
  std::vector<double> nx, ny;   // unit normal from i to j
  std::vector<double> area;     // overlap area, m^2
  std::vector<double> inv_lc;   // 1/L_c = (1/r_i + 1/r_j)/2, m^-1
  std::vector<double> fn;       // normal force on i along n (elastic + damping), N; negative = repulsive
  // The force on i summed over the terms that ran (zero after ContactSearch::find, resize and clear_forces;
  // each term adds its own), and scratch for the power of the last term (one slot per contact).
  std::vector<PairForce> pair_force;
  std::vector<double> pair_power;
  std::size_t size() const { return i.size(); }
  void clear();
  // Makes room for `count` contacts (entries not yet set; new pair forces zero) and zeroes the diagnostics.
  void resize(std::size_t count);
  // Sets every contact's summed force back to zero.
  void clear_forces();
  // Diagnostics of the last search.
  std::int64_t candidate_pairs = 0;  // pairs whose bounding circles overlap
  std::int64_t enclosed = 0;         // overlaps without a contact line (one polygon inside another)
  std::int64_t multi_crossing = 0;   // more than 2 crossings (a corner poked through)
};

class ContactSearch {
 public:
  ContactSearch() = default;
  ContactSearch(const mesh::CellMesh& mesh, const Bodies& bodies);
  // Finds every overlapping pair at state q and fills `out` (cleared first).
  void find(std::span<const double> q, ContactList& out);
  // How often the neighbour list was rebuilt.
  std::int64_t rebuilds() const { return rebuilds_; }

 private:
  bool world_vertices_and_staleness(std::span<const double> q);
  std::span<const Vec2> world_polygon(std::size_t k) const {
    const auto& off = mesh_->vertex_offset;
    return {world_.data() + off[k], static_cast<std::size_t>(off[k + 1] - off[k])};
  }
  const mesh::CellMesh* mesh_ = nullptr;
  const Bodies* bodies_ = nullptr;
  std::vector<Vec2> world_;               // vertices of every cell in world coordinates
  std::vector<double> inv_diameter_;      // 1/r of every cell, m^-1
  std::vector<double> edge_reach_;        // geometry::edge_reach of every edge (indexed like the vertices), m
  std::vector<std::int32_t> cell_start_;  // counting sort of cells into grid cells
  std::vector<std::int32_t> cell_of_;
  std::vector<std::int32_t> sorted_;
  void rebuild(std::span<const double> q);
  bool test_pair(std::size_t p, const double* x, const double* y, double slack);
  // Verlet list: pairs whose bounding circles come within `skin_` of each other, rebuilt when some
  // vertex may have moved by more than skin/2 since the last build (centroid displacement plus bounding
  // radius times rotation), so no pair can start to overlap unseen.
  double skin_ = 0;
  std::vector<double> ref_;  // q at the last build
  struct NeighbourPair {
    std::int32_t i, j;
    std::int32_t edge_i, edge_j;  // the facing edges that last separated the pair (first vertex index)
    bool overlapping;             // the pair overlapped at the last search
    geometry::OverlapLines lines; // the lines of its last overlap (convex_overlap's cache)
  };
  std::vector<NeighbourPair> neighbours_;
  std::vector<NeighbourPair> previous_;       // the list before the last rebuild
  std::vector<std::int32_t> previous_first_;  // its first pair of each cell i (pairs are in order of i)
  std::vector<std::vector<NeighbourPair>> thread_pairs_;  // the rebuild's per-thread buffers
  struct Block {  // one thread's block of pairs in the list fill
    std::int64_t count = 0, enclosed = 0, multi_crossing = 0;  // overlapping pairs and their diagnostics
    std::int64_t offset = 0;                                   // its first entry in the list
  };
  void fill_contacts(std::size_t first, std::size_t last, Block& block, ContactList& out);
  std::vector<Block> blocks_;
  HomeFirstSchedule pair_schedule_;  // the pair tests: each thread its cells' pairs first
  std::int64_t rebuilds_ = 0;
  enum class PairState : std::uint8_t { apart, candidate, overlapping };  // bounding circles apart; overlap
  std::vector<PairState> pair_state_;                // one slot per neighbour pair (filled in parallel)
  std::vector<geometry::ContactGeometry> geometry_;  // one slot per neighbour pair, set where overlapping
};

struct ContactParameters {
  double grain_modulus, thickness, gamma_n, gamma_t, friction;
};

// The force terms. q, v: state and velocities (flat layout of bodies.hpp). Each adds its force on every
// contact to the contact's pair_force (equal and opposite on j, acting at R) and returns the power it delivers
// to the bodies, W. add_contact_forces then adds the contacts' summed forces and their torques to the cells'
// forces f (same layout), once for all the terms that ran.
double contact_elastic(ContactList& c, const ContactParameters& p, const Bodies& bodies, std::span<const double> q,
                       std::span<const double> v);
double contact_damping(ContactList& c, const ContactParameters& p, const Bodies& bodies, std::span<const double> q,
                       std::span<const double> v);
double contact_friction(ContactList& c, const ContactParameters& p, const Bodies& bodies,
                        std::span<const double> q, std::span<const double> v);
void add_contact_forces(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f);

}  // namespace frac::dem
