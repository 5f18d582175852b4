#pragma once
// The search for contacts between cells (physics/polygon-dem.md §3): the pairs of a neighbour list
// (dem/neighbour_list) culled by bounding circles and separating edges before any clipping, and the overlap
// geometry of each candidate pair (geometry/overlap), into a ContactList (dem/contact_list) whose forces the
// contact laws (dem/contact_laws) then give.
// As phases of the model's step (core/phases): each thread tests its part of the pairs in order, the first
// thread putting its contacts straight into the list, the others into lists of their own, copied in behind it in
// pair order, so the list does not depend on the thread count. Its room grows with the contacts, not with the
// pairs (far fewer: memory).
// The overlap of a pair gets a hint (geometry::OverlapHint): the cached facing edges and their reaches,
// precomputed per cell edge, which leave out clip lines that cannot cut.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_list.hpp"
#include "dem/neighbour_list.hpp"
#include "geometry/overlap.hpp"
#include "geometry/vec2.hpp"

namespace frac::dem {

using geometry::Vec2;

class ContactSearch {
 public:
  ContactSearch() = default;
  ContactSearch(const mesh::CellMesh& mesh, const Bodies& bodies);
  // Finds every overlapping pair at state q and fills `out` (cleared first): its phases on a team of their own.
  void find(std::span<const double> q, ContactList& out);
  // The same as phases of a caller's step, which may run other phases between the two lists (the model: the
  // beams): bind(q, out) before each run (outside the team); start_phases, the world vertices and the moves of
  // the cells from their positions alone; finish_phases, the neighbour list when it is due, the pair tests and
  // the list filled (thread t of the team its block, out.block[t]), its size and diagnostics. The phases call
  // this object: take them once it is in place.
  void bind(std::span<const double> q, ContactList& out);
  Phases start_phases();
  Phases finish_phases();
  // How often the neighbour list was rebuilt.
  std::int64_t rebuilds() const { return list_.rebuilds(); }
  // The neighbour list's state (core/state_archive); loading checks every edge and vertex index against the mesh.
  void visit_state(StateArchive& archive);

 private:
  void reserve_threads(std::size_t threads, ContactList& out);
  // The phases' bodies: t of a team of nt.
  void vertices(std::size_t t, std::size_t nt);    // world vertices and moves of thread t's cells
  void test_pairs(std::size_t t, std::size_t nt);  // thread t's part of the pairs into its list
  void count(std::size_t nt);                      // the blocks' offsets, the list's room, size and diagnostics
  void fill(std::size_t t, std::size_t nt);        // thread t's contacts copied to its block of the list
  std::span<const double> q_;                      // bound state and list
  ContactList* out_ = nullptr;
  WorldPolygons world_polygons() const { return {world_.data(), mesh_->vertex_offset.data()}; }
  std::span<const Vec2> world_polygon(std::size_t k) const { return world_polygons()(k); }
  const mesh::CellMesh* mesh_ = nullptr;
  const Bodies* bodies_ = nullptr;
  std::vector<Vec2> world_;           // vertices of every cell in world coordinates
  std::vector<double> inv_diameter_;  // 1/r of every cell, m^-1
  std::vector<double> edge_reach_;    // geometry::edge_reach of every edge (indexed like the vertices), m
  NeighbourList list_;
  // Where a thread puts the contacts of the pairs it tests in order: `out`'s entries from `next` on (`out` grows).
  struct Fill {
    ContactList* out;
    std::size_t next;
    std::int64_t enclosed, multi_crossing;
    // At entry next, counted in the diagnostics.
    void put(std::int32_t i, std::int32_t j, const geometry::ContactGeometry& geo, double inv_lc);
  };
  bool test_pair(std::size_t p, const double* x, const double* y, double slack, Fill& fill);
  [[gnu::noinline]] void test_pair_further(std::size_t p, const double* x, const double* y, double slack, Fill& fill);
  TeamSlots<std::int64_t> candidates_;  // per thread: candidate pairs it tested
  struct Block {                        // one thread's block of the list: the contacts of its part of the pairs
    std::int64_t count = 0, enclosed = 0, multi_crossing = 0;  // overlapping pairs and their diagnostics
    std::int64_t offset = 0;                                   // its first entry in the list
  };
  std::vector<Block> blocks_;        // per thread
  std::vector<ContactList> staged_;  // per thread but the first: the contacts of its part of the pairs
  // Thread t's part of the pairs, of a team of nt: whole chunks of kChunkPairs, split by the last evaluation's
  // contacts (each costs the pair tests of about kContactWeight pairs without one).
  static constexpr std::size_t kChunkPairs = 1024;
  static constexpr double kContactWeight = 16;
  Range balanced_part(std::size_t t, std::size_t nt) const;
  std::array<std::vector<std::uint32_t>, 2>
      chunk_contacts_;  // contacts per chunk: the last evaluation's, and this one's
  int parity_ = 0;      // chunk_contacts_[parity_]: this evaluation's
  // out.touch for thread t's block, [first, last), of a team of nt.
  void set_touch(ContactList& out, std::size_t t, std::size_t first, std::size_t last, std::size_t nt) const;
};

}  // namespace frac::dem
