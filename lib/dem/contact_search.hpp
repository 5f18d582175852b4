#pragma once
// The search for contacts between cells (physics/polygon-dem.md §3): neighbour search on a cell list with cells
// of the largest polygon diameter, pairs culled by bounding circles before any clipping, and the overlap
// geometry of each candidate pair (geometry/overlap), into a ContactList (dem/contact_list) whose forces the
// contact laws (dem/contact_laws) then give.
// Threads share the neighbour-list rebuild (contiguous ranges of cells, joined in order) and the neighbour
// pairs (circle test, separating edges, overlap geometry): each thread tests its cells' pairs in order and puts
// their contacts straight into the list, a thread done with its own tests the others' last pairs into the
// pairs' slots, and the blocks are joined in pair order, so the list does not depend on the thread count. All
// of this runs on one team of threads (core/parallel.hpp, core/thread_team.hpp), with the model's other loops.
// The overlap of a pair gets a hint (geometry::OverlapHint): the cached facing edges and their reaches,
// precomputed per cell edge, which leave out clip lines that cannot cut.
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_list.hpp"
#include "geometry/overlap.hpp"
#include "geometry/vec2.hpp"

namespace frac::dem {

using geometry::Vec2;

class ContactSearch {
 public:
  ContactSearch() = default;
  ContactSearch(const mesh::CellMesh& mesh, const Bodies& bodies);
  // Finds every overlapping pair at state q and fills `out` (cleared first), on threads of its own: call it
  // outside a parallel region.
  void find(std::span<const double> q, ContactList& out);
  // The same in parts, for a caller that runs other work on the same team in between (the model: the
  // beams). Before the team: reserve_threads. Team functions: find_start (the world vertices of this thread's
  // cells, from their positions alone; no barrier at its end); after a barrier, find_finish (the neighbour
  // list, the pair tests, the list filled: thread t its block, out.block[t]; no barrier at its end). After a
  // barrier, by one thread: find_end (the list's size, `blocks` and diagnostics).
  void reserve_threads(std::size_t threads, ContactList& out);
  void find_start(std::span<const double> q, const ContactList& out);
  void find_finish(std::span<const double> q, ContactList& out);
  void find_end(ContactList& out);
  // How often the neighbour list was rebuilt.
  std::int64_t rebuilds() const { return rebuilds_; }

 private:
  void world_vertices_and_staleness(std::span<const double> q);  // this thread's cells; into stale_
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
  struct GridBody {  // a body's centre and bounding radius, in grid order (sorted_)
    double x, y, r;
    std::int32_t index;
  };
  std::vector<GridBody> grid_body_;
  void rebuild(std::span<const double> q, ContactList& out);  // a team function, barriers at its ends
  // Where a thread puts the contacts of the pairs it tests in order: the list's entries from `next` on.
  struct PairContact;
  struct Fill {
    ContactList* out;
    std::size_t next;
    std::int64_t enclosed, multi_crossing;
    void put(const PairContact& contact);  // at entry next, counted in the diagnostics
  };
  // (fill: null for a pair another thread's part holds: its contact goes to the pair's slot.)
  bool test_pair(std::size_t p, const double* x, const double* y, double slack, Fill* fill);
  [[gnu::noinline]] void test_pair_further(std::size_t p, const double* x, const double* y, double slack, Fill* fill);
  // Verlet list: pairs whose bounding circles come within `skin_` of each other, rebuilt when two cells'
  // centroids may together have moved by more than the skin since the last build, so no pair can start to
  // overlap unseen.
  double skin_ = 0;
  std::vector<double> ref_;  // q at the last build
  struct NeighbourPair {
    std::int32_t i, j;
    std::int32_t edge_i, edge_j;  // the facing edges that last separated the pair (first vertex index)
    bool overlapping;             // the pair overlapped at the last search
    std::uint8_t deepest_i, deepest_j;  // the vertices of P_j and P_i deepest along edge_i's and edge_j's normals
    geometry::OverlapLines lines; // the lines of its last overlap (convex_overlap's cache)
  };
  std::vector<NeighbourPair> neighbours_;
  std::vector<NeighbourPair> previous_;       // the list before the last rebuild
  std::vector<std::int32_t> previous_first_;  // its first pair of each cell i (pairs are in order of i)
  std::vector<std::vector<NeighbourPair>> thread_pairs_;  // the rebuild's per-thread buffers
  std::size_t grid_x_ = 0, grid_y_ = 0;                   // the rebuild's grid (0: no finite grid)
  struct Moved {  // the two largest distances that cells' centroids moved since the build, m
    double largest = 0, second = 0;
    void add(double d) {
      if (d > largest) {
        second = largest;
        largest = d;
      } else if (d > second) {
        second = d;
      }
    }
  };
  TeamSlots<Moved> moved_;                                // per thread
  TeamSlots<std::int64_t> candidates_;                    // per thread: candidate pairs it tested
  std::size_t teams_ = 1;                                 // threads of the team of the last find
  struct Block {  // one thread's block of the list: the contacts of its part of the pairs
    std::int64_t count = 0, enclosed = 0, multi_crossing = 0;  // overlapping pairs and their diagnostics
    std::int64_t offset = 0;                                   // its first entry in the list
  };
  std::vector<Block> blocks_;  // per thread
  HomeFirstSchedule pair_schedule_;  // the pair tests: each thread its cells' pairs first
  TeamSlots<std::size_t> own_contacts_;  // per thread: the contacts of the pairs it tested of its own part
  TeamSlots<char> room_;                 // per thread: whether the list had room for every pair (find_start)
  // The overlapping pairs of [first, last) that went to their slots; their contacts, in pair order, into `fill`.
  std::size_t overlapping_pairs(std::size_t first, std::size_t last) const;
  void fill_from_slots(std::size_t first, std::size_t last, Fill& fill) const;
  // out.touch for this thread's block, [first, last), of a team of nt.
  void set_touch(ContactList& out, std::size_t first, std::size_t last, std::size_t nt) const;
  std::int64_t rebuilds_ = 0;
  enum class PairState : std::uint8_t { apart, candidate, overlapping };  // bounding circles apart; overlap
  std::vector<PairState> pair_state_;                // one slot per neighbour pair (filled in parallel)
  // An overlapping pair's entry of the list, whole in one cache line (ContactGeometry has 96 bytes): the thread
  // that fills the entry reads this line only, not the pair's nor the cells' (written or read by the other
  // thread: lines that would cross between the cores).
  struct alignas(64) PairContact {
    double rx, ry, nx, ny, area;
    bool enclosed, multi_crossing;  // kind enclosed; more than two distinct crossings
    std::int32_t i, j;
    double inv_lc;  // 1/L_c of the pair
  };
  std::vector<PairContact> geometry_;  // one slot per neighbour pair, set where overlapping
};

}  // namespace frac::dem
