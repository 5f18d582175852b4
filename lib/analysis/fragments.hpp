#pragma once
// Fragments of a polygon-DEM state (docs/physics/polygon-dem.md §9): the connected components of
// the cells through intact beams (contacts do not bind), found by union-find, and per fragment its
// mass, cell count, centre of mass, velocity of the centre of mass and kinetic energies.
//
// Numbering: fragments are sorted by mass, largest first; equal masses by their smallest cell index.
// Each fragment is summed in increasing cell index, so the ids and the numbers do not depend on how
// the cells and beams are numbered (up to rounding of the sums, and to exact ties in mass).
//
// Kinetic energies of fragment f with mass M, centre-of-mass velocity V:
//   translational  T_f = M |V|^2 / 2
//   rotational     R_f = sum over its cells k of  m_k |v_k - V|^2 / 2 + I_k w_k^2 / 2
// R_f is the kinetic energy in the fragment's centre-of-mass frame: the spin of each cell about its
// own centroid plus the motion of the cells about the fragment's centre of mass (for a rigid fragment
// its rotation; for a deforming one also its internal vibration). T_f + R_f is the total kinetic
// energy of the fragment's cells (König's theorem); R_f is summed directly, never as a difference, so
// it is never negative and keeps its relative precision for a fast fragment that barely rotates.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/log_histogram.hpp"

namespace frac::analysis {

// One state of the cells: views of the arrays of a run frame (io/run_io) and of its mesh.
struct CellState {
  std::span<const double> mass;              // [N] kg
  std::span<const double> inertia;           // [N] kg m^2, moment of inertia about the centroid
  std::span<const double> position;          // [2N] m, centroids, x0 y0 x1 y1 ...
  std::span<const double> velocity;          // [2N] m/s
  std::span<const double> angular_velocity;  // [N] rad/s
  std::span<const std::int64_t> beam;        // [2B] cell pairs a0 b0 a1 b1 ...
  std::span<const std::uint8_t> intact;      // [B] nonzero = intact
};

struct Fragments {
  std::vector<std::int64_t> cell_fragment;           // [N] fragment id of each cell
  std::vector<double> mass;                          // [F] kg, decreasing
  std::vector<std::int64_t> cell_count;              // [F]
  std::vector<std::int64_t> first_cell;              // [F] smallest cell index of the fragment
  std::vector<double> center_of_mass;                // [2F] m
  std::vector<double> velocity;                      // [2F] m/s, of the centre of mass
  std::vector<double> kinetic_energy_translational;  // [F] J
  std::vector<double> kinetic_energy_rotational;     // [F] J, in the centre-of-mass frame
  double total_mass = 0.0;                           // kg, sum over all cells

  // total_mass / N: a fragment of k cells weighs about k times this.
  double mean_cell_mass() const;

  std::size_t fragments() const { return mass.size(); }
  // Fragments of at least `min_cells` cells, and of exactly one cell.
  std::size_t count_at_least(std::int64_t min_cells) const;
  std::size_t singles() const { return count_at_least(1) - count_at_least(2); }
  // Masses of the fragments of at least `min_cells` cells (the sample of the mass distribution).
  std::vector<double> masses_at_least(std::int64_t min_cells) const;
};

// Union-find over N elements (path halving, union by size), reusable without reallocation.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }
  void reset(std::size_t n);
  std::int64_t find(std::int64_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(std::int64_t a, std::int64_t b);
  std::size_t size() const { return parent_.size(); }
  // Number of elements in the set of `root` (a value returned by find).
  std::int64_t set_size(std::int64_t root) const { return size_[root]; }

 private:
  std::vector<std::int64_t> parent_, size_;
};

// Checks that the state's arrays agree in size and the beams name cells in range; InputError
// naming the array at fault otherwise.
void check_state(const CellState& s);

// The fragments of a state (check_state first).
Fragments find_fragments(const CellState& s);

// Fragment count and largest fragment mass only, for the frames of a time series: the masses and
// beams of the run with one frame's intact flags. Keeps its workspace between calls, so counting
// every frame of a run allocates nothing after the first.
struct FragmentCount {
  std::int64_t count = 0;     // fragments of at least min_cells cells
  double largest_mass = 0.0;  // kg, the largest fragment, whatever its cell count
};
class FragmentCounter {
 public:
  FragmentCount operator()(std::span<const double> mass, std::span<const std::int64_t> beam,
                           std::span<const std::uint8_t> intact, std::int64_t min_cells);

 private:
  UnionFind uf_;
  std::vector<double> root_mass_;  // compensated sum (value, error) per root
};

// Log-binned density histogram (analysis/log_histogram: bins [10^(j/b), 10^((j+1)/b)) kg with their edges
// moved halfway between the cell-count clusters of the mean cell mass, density = count / (n width) in
// kg^-1) of the masses of the fragments of at least `min_cells` cells. No bins when no fragment is that
// large. UsageError for bins_per_decade <= 0.
LogHistogram mass_histogram(const Fragments& f, std::int64_t min_cells, double bins_per_decade);

}  // namespace frac::analysis
