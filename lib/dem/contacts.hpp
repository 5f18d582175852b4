#pragma once
// Contacts between cells (physics/polygon-dem.md §3): neighbour search on a cell list with cells of
// the largest polygon diameter, pairs culled by bounding circles before any clipping, the overlap
// geometry of each candidate pair (geometry/overlap), and the three contact force terms, each a separate
// unit that runs only when the scene turns it on (the engine runs the scene's terms in one pass over the
// contact list, contact_terms, compiled for that set of terms):
//   contact_elastic   F_n = −Y·A·h/L_c along n, at the contact line's midpoint R
//   contact_damping   + m_eff·γ_N·v_n along n (v_n < 0 while approaching)
//   contact_friction  F_t = sign(v_t)·min(m_eff·γ_T·|v_t|, μ·|F_n|) along t = ẑ × n
// Every pair force is equal and opposite and acts at one point, so momentum and angular momentum are
// conserved exactly. Each term returns the power it delivers to the bodies (W) for the energy ledger, and
// adds its force to each contact's slot; one pass (add_contact_forces) then adds the contacts' forces, summed
// over the terms, to the cells.
// Threads share the neighbour-list rebuild (contiguous ranges of cells, joined in order) and the neighbour
// pairs (circle test, separating edges, overlap geometry): each thread tests its cells' pairs in order and puts
// their contacts straight into the list, a thread done with its own tests the others' last pairs into the
// pairs' slots, and the blocks are joined in pair order; the contact terms run on each thread's block, and the
// contacts' forces are added to the cells in contact order, so results do not depend on the thread count. All
// of this runs on one team of threads (core/parallel.hpp, core/thread_team.hpp), with the model's other loops.
// The overlap of a pair gets a hint (geometry::OverlapHint): the cached facing edges and their reaches,
// precomputed per cell edge, which leave out clip lines that cannot cut.
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

// The contact terms, in the order the engine runs them.
enum class ContactTerm : int { elastic = 0, damping, friction, count };

struct ContactList {
  // Per contact, in entries [0, size()); the arrays may be longer (room kept from list to list).
  std::vector<std::int32_t> i, j;
  std::vector<double> rx, ry;   // application point R, m
  std::vector<double> nx, ny;   // unit normal from i to j
  std::vector<double> area;     // overlap area, m^2
  std::vector<double> inv_lc;   // 1/L_c = (1/r_i + 1/r_j)/2, m^-1
  std::vector<double> fn;       // normal force on i along n (elastic + damping), N; negative = repulsive
  // The force on i summed over the terms that ran (zero after ContactSearch::find and clear_forces;
  // each term adds its own), and the power of each term on each contact (summed by contact_power).
  std::vector<PairForce> pair_force;
  std::array<std::vector<double>, static_cast<std::size_t>(ContactTerm::count)> term_power;
  // The power of each term summed over fixed blocks of kPowerBlock contacts, in contact order within a block
  // (contact_block_powers; contact_power adds them up in block order): the same grouping whatever the
  // thread count, so a team sums its own blocks without reading much of what the others wrote.
  static constexpr std::size_t kPowerBlock = 256;
  std::array<std::vector<double>, static_cast<std::size_t>(ContactTerm::count)> block_power;
  std::size_t size() const { return count_; }  // (set by ContactSearch::find_end)
  // Room for `count` contacts (never shrinks; the size is unchanged).
  void reserve(std::size_t count);
  std::size_t room() const { return i.size(); }
  // Entries [from, from + count) copied to [to, to + count), to ≤ from (the search's fill).
  void move_entries(std::size_t from, std::size_t to, std::size_t count);
  // Sets every contact's summed force back to zero.
  void clear_forces();
  // Diagnostics of the last search.
  std::int64_t candidate_pairs = 0;  // pairs whose bounding circles overlap
  std::int64_t enclosed = 0;         // overlaps without a contact line (one polygon inside another)
  std::int64_t multi_crossing = 0;   // more than 2 crossings (a corner poked through)
  // The contacts that thread t of the team that filled the list wrote, [block[t].first, block[t].last), for
  // the `blocks` threads of that team (the search's last step sets them): the contact terms run on these on
  // the same team, each thread on the contacts it wrote, with no barrier between.
  std::vector<Range> block;
  std::size_t blocks = 0;
  // touch[t·blocks + u]: the entries of block t from the first to the last that touches a cell of thread u's
  // part of the cells (static_range of the cells over `blocks` threads); empty if none: a thread adding the
  // forces onto its cells reads only those of the other threads' blocks (set by the search).
  std::vector<Range> touch;
  // This thread's contacts: its block when the team that filled the list is the calling team, else its
  // static part.
  Range mine() const;

 private:
  friend class ContactSearch;
  std::size_t count_ = 0;
};

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

struct ContactParameters {
  double grain_modulus, thickness, gamma_n, gamma_t, friction;
};

// The force terms. q, v: state and velocities (flat layout of bodies.hpp). Each adds its force on every
// contact to the contact's pair_force (equal and opposite on j, acting at R) and returns the power it delivers
// to the bodies, W. add_contact_forces then adds the contacts' summed forces and their torques to the cells'
// forces f (same layout), once for all the terms that ran. Each term runs on threads of its own (call it
// outside a parallel region). contact_term, a team function (core/parallel.hpp), runs one on the contacts
// [first, last) (a team's part; the terms of one contact in engine order on one thread, since damping adds
// to fn and friction reads it), and contact_power sums a term's power over the list, block by block.
double contact_elastic(ContactList& c, const ContactParameters& p, const Bodies& bodies, std::span<const double> q,
                       std::span<const double> v);
double contact_damping(ContactList& c, const ContactParameters& p, const Bodies& bodies, std::span<const double> q,
                       std::span<const double> v);
double contact_friction(ContactList& c, const ContactParameters& p, const Bodies& bodies,
                        std::span<const double> q, std::span<const double> v);
void contact_term(ContactTerm term, ContactList& c, const ContactParameters& p, const Bodies& bodies,
                  std::span<const double> q, std::span<const double> v, Range contacts);
// The same for several terms at once, `terms` a set of bits (contact_term_bit): each contact's terms in engine
// order in one pass over the contacts, with the same results as the terms one after another.
constexpr unsigned contact_term_bit(ContactTerm t) { return 1u << static_cast<unsigned>(t); }
void contact_terms(unsigned terms, ContactList& c, const ContactParameters& p, const Bodies& bodies,
                   std::span<const double> q, std::span<const double> v, Range contacts);
double contact_power(const ContactList& c, ContactTerm term);
// A team function, after a barrier behind every term: the sums of a term's power over the blocks of the list
// (its first `count` contacts) that start in `mine`, this thread's part of it. After the team,
// contact_power_of_blocks adds them up in block order: the same bits as contact_power.
void contact_block_powers(ContactList& c, ContactTerm term, std::size_t count, Range mine);
double contact_power_of_blocks(const ContactList& c, ContactTerm term);
void add_contact_forces(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f);
// The same for the first `count` contacts of the list and the cells in `cells` only (a team's part: each
// thread its cells, the same bits as the whole pass).
void add_contact_forces(const ContactList& c, std::size_t count, std::size_t n, std::span<const double> q,
                        std::span<double> f, Range cells);
// The same, a team function on the team that filled the list (after a barrier behind every term): each thread
// onto its part of the cells, reading its own block and, of the others, only the entries that touch its cells
// (ContactList::touch). The blocks [blocks.first, blocks.last) only, in block order (a caller that adds the
// first block before that barrier, on the first thread, and the others after it, adds them in the same order).
void add_contact_forces_of_team(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f,
                                Range blocks = {0, SIZE_MAX});

}  // namespace frac::dem
