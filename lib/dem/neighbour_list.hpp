#pragma once
// The Verlet list of the contact search (physics/polygon-dem.md §3): the pairs of cells whose bounding circles
// come within a skin of each other, from a cell list (grid cells of the largest bounding diameter plus the
// skin), rebuilt when two cells may together have moved by more than the skin since the last build, so that no
// pair can start to overlap unseen. A pair found again at a rebuild keeps what the pair tests learnt about it.
// A rebuild is three phases of a step (core/phases): the grid (serial), the pairs (threads take contiguous ranges
// of cells into buffers of their own) and the join of the buffers in thread order (serial), so the list does not
// depend on the thread count.
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.hpp"
#include "core/state_archive.hpp"
#include "dem/bodies.hpp"
#include "geometry/overlap.hpp"
#include "geometry/vec2.hpp"

namespace frac::dem {

// A pair of cells i < j of the list, with what the pair tests (dem/contact_search) learnt about it.
// (Edge and vertex indices in a byte: a contact polygon has at most kMaxContactPolygonVertices.)
static_assert(geometry::kMaxContactPolygonVertices <= 256);
struct NeighbourPair {
  std::int32_t i, j;
  std::uint8_t edge_i, edge_j;        // the facing edges that last separated the pair (first vertex index)
  bool overlapping;                   // the pair overlapped at the last search
  std::uint8_t deepest_i, deepest_j;  // the vertices of P_j and P_i deepest along edge_i's and edge_j's normals
  geometry::OverlapLines lines;       // the lines of its last overlap (convex_overlap's cache)
};

// The cells' polygons in world coordinates: cell k's vertices are vertex[offset[k] .. offset[k + 1]).
struct WorldPolygons {
  const geometry::Vec2* vertex;
  const std::int64_t* offset;
  std::span<const geometry::Vec2> operator()(std::size_t k) const {
    return {vertex + offset[k], static_cast<std::size_t>(offset[k + 1] - offset[k])};
  }
};

class NeighbourList {
 public:
  NeighbourList() = default;
  explicit NeighbourList(const Bodies& bodies);
  // Before a team of `threads` uses the list (allocates when the count grows).
  void reserve_threads(std::size_t threads);
  // Thread t's part of a parallel phase (of nt): how far its cells (static_range) have moved since the build, at
  // state q (x of every cell, then y, then φ).
  void measure_moves(std::span<const double> q, std::size_t t, std::size_t nt);
  // In a phase after measure_moves's (on any thread of its team of nt): whether the list must be rebuilt.
  bool stale(std::size_t nt) const;
  // A rebuild at state q, in three phases: build_grid (serial; then rebuilding() holds until end_rebuild, in a
  // phase after the join: the phases' `when` reads it), find_pairs (parallel: thread t's part of the cells, a new
  // pair's facing edges from `world`) and join (serial).
  void build_grid(std::span<const double> q);
  bool rebuilding() const { return rebuilding_; }
  void end_rebuild() { rebuilding_ = false; }
  void find_pairs(std::span<const double> q, WorldPolygons world, std::size_t t, std::size_t nt);
  void join(std::size_t nt);
  std::span<NeighbourPair> pairs() { return pairs_; }
  std::size_t size() const { return pairs_.size(); }
  // How often the list was built.
  std::int64_t rebuilds() const { return rebuilds_; }
  // The state a continuation needs (core/state_archive): the positions at the last build and the pairs with what
  // the pair tests learnt about them (which changes the bits of later steps). Loading checks the cells' indices;
  // the caller checks the edges and vertices (dem/contact_search).
  void visit_state(StateArchive& archive);

 private:
  const Bodies* bodies_ = nullptr;
  bool rebuilding_ = false;
  double skin_ = 0;                           // m
  std::vector<double> ref_;                   // q at the last build
  std::vector<NeighbourPair> pairs_;          // in order of i, then of j
  std::vector<NeighbourPair> previous_;       // the list before the rebuild under way (empty between rebuilds)
  std::vector<std::int32_t> previous_first_;  // its first pair of each cell i
  std::vector<std::vector<NeighbourPair>> thread_pairs_;  // the rebuild's buffers of the threads after the first
  // Counting sort of the cells into the grid, and their centres and bounding radii in grid order (sorted).
  std::vector<std::int32_t> cell_start_, cell_of_, sorted_;
  struct GridBody {
    double x, y, r;
    std::int32_t index;
  };
  std::vector<GridBody> grid_body_;
  std::size_t grid_x_ = 0, grid_y_ = 0;  // grid cells along x and y (0: no finite grid)
  struct Moved {                         // the two largest distances that cells' centroids moved since the build, m
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
  TeamSlots<Moved> moved_;  // per thread
  std::int64_t rebuilds_ = 0;
};

}  // namespace frac::dem
