#pragma once
// The force and energy loops of the rubber lattice, written once over the bond-law evaluators
// (bond_law.hpp) and instantiated for each combination of laws, three-body weight and damping. Three
// passes, each a loop over nodes split into contiguous ranges across the threads:
//
//   1. bonds:   for each forward bond b (3 per node): bond vector, h, h'/u, f'/u, the damping
//               coefficient, once per bond (the exponential of h is the costly part); whether it fails at
//               these positions (failures.hpp).
//   2. centres: for each node i, the derivative D(i,s) = ∂E_i/∂x_j of its own energy
//               E_i = Σ_s f(u_s) + Σ_{s≠t} h_s h_t g(a_s·a_t) with respect to each neighbour j = nbr(i,s).
//               For a quadratic g (Marder's) the three-body sum is written through the moments
//               S = Σ h a, M = Σ h a aᵀ (O(6) work instead of the 30 ordered pairs):
//                 T = c2(‖M‖² − Σh²|a|⁴) + c1(|S|² − Σh²|a|²) + c0((Σh)² − Σh²).
//               With the three-body weight all_bonds (bond_law.hpp) the node's three-body part is
//               W T, W = Π_s h_s, and D carries T ∂W/∂a_s as well (a separate instantiation).
//               With energy-neutral failure, a node whose bond failed in this evaluation first freezes
//               the terms that contain it (forces.cpp, freeze_failing).
//   3. gather:  F_i = Σ_s D(i,s) − Σ_s D(nbr(i,s), s+3 mod 6)   (translation invariance of E_i),
//               plus Kelvin damping along bonds; a_i = F_i / m.
//
// Each node's force is summed by the same instructions in the same order whichever thread computes
// it (a gather, not a scatter): results are bit-identical for any number of threads. Energy sums are
// taken over fixed blocks of nodes and the block sums added in order, for the same reason.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "rubber/bond_law.hpp"

namespace frac::rubber {

// Per forward bond, recomputed every force evaluation.
struct BondData {
  double bx, by;  // bond vector x_j − x_i (+ periodic image shift), m
  double h;       // cut-off h(u)
  double hpu;     // h'(u)/u
  double fpu;     // f'(u)/u
  double kel;     // Kelvin damping coefficient β_b/u² (0 when damping is off)
};

enum class DampingKind { none, uniform, near_failure };

// Bond status (per forward bond).
inline constexpr std::uint8_t kIntact = 0;
inline constexpr std::uint8_t kRemoved = 1;  // missing, or cut on purpose (seed crack): no energy, no force
inline constexpr std::uint8_t kBroken = 2;   // failed irreversibly: keeps the constant 2 f(u_c), no force
// Failed at this evaluation's positions under energy-neutral failure (ForceContext::freeze): the centres of its
// two ends freeze its three-body terms; settle_failures (failures.hpp) makes it kBroken after the evaluation.
inline constexpr std::uint8_t kFreezing = 3;

// Everything the passes read and write. Owned by the model; the pointers stay valid for its life.
struct ForceContext {
  std::size_t n = 0;
  const std::int32_t* nbr = nullptr;    // [6(n+1)]
  std::uint8_t* status = nullptr;       // [3(n+1)]
  std::uint8_t* past_cutoff = nullptr;  // [3(n+1)] 0 never beyond u_c, 1 beyond (event not yet recorded), 2 recorded
  const double* cutoff = nullptr;       // [3(n+1)] u_c per bond
  const double* shift = nullptr;        // [6(n+1)] lab image shifts, or nullptr without periodic bonds
  BondData* bond = nullptr;             // [3(n+1)]
  double* D = nullptr;                  // [12(n+1)] D(i,s) as (x, y)

  // The three-body residual (three_body_residual.hpp): c_st, 6 × 6, or nullptr (the paper's law).
  const double* residual = nullptr;

  // Dynamics: events and irreversible breaking (failures.hpp) happen only when `track` is set.
  bool track = false;
  double break_extra = 0;  // irreversible breaking when u > u_c + break_extra; +inf: never (reversible law)
  // Energy-neutral failure: a bond breaks when it first passes u_c (break_extra is not used), and the
  // three-body terms that contain it are frozen into the constant energy of their node, frozen[i].
  bool freeze = false;
  double* frozen = nullptr;                           // [n] J, with freeze
  const double *x_prev = nullptr, *y_prev = nullptr;  // with freeze: positions at the previous step, or nullptr
  double beta = 0;                                    // Kelvin coefficient β (kg/s)
  double damping_onset = 0;  // near_failure: damping ramps from 0 at this length (m) to β at u_c

  const double *x = nullptr, *y = nullptr, *vx = nullptr, *vy = nullptr;
  double *ax = nullptr, *ay = nullptr;
  double inv_mass = 1;

  // Per worker (up to kMaxWorkers): counts of bonds newly beyond u_c, of bonds broken, of nodes with
  // a non-finite force.
  static constexpr int kMaxWorkers = 64;
  int events[kMaxWorkers] = {};
  int breaks[kMaxWorkers] = {};
  int nonfinite[kMaxWorkers] = {};

  // Energy: block partial sums (pair, three-body), block = kEnergyBlock nodes.
  static constexpr std::size_t kEnergyBlock = 1024;
  double* block_energy = nullptr;  // [4 · blocks]
};

// After bonds and centres: the virial Σ_i Σ_s D(i,s) ⊗ a(i,s) (J) of the energy blocks [k0, k1) into
// block_energy as (xx, xy, yx, yy) per block.
void virial_blocks(ForceContext& c, std::size_t k0, std::size_t k1);

// The passes of one combination of laws, over a range of nodes [i0, i1), with their evaluators; the model
// schedules them (three passes over all nodes, or fused row by row so that the bond data and D stay in cache).
class ForcePasses {
 public:
  virtual ~ForcePasses() = default;
  virtual void bonds(ForceContext& c, std::size_t i0, std::size_t i1, int worker) const = 0;
  virtual void centres(ForceContext& c, std::size_t i0, std::size_t i1) const = 0;
  virtual void gather(ForceContext& c, std::size_t i0, std::size_t i1, int worker) const = 0;
  // After bonds (with track = false): pair energy Σ 2f over bonds and three-body energy Σ T_i of the
  // energy blocks [k0, k1), into block_energy.
  virtual void energy(ForceContext& c, std::size_t k0, std::size_t k1) const = 0;
};

std::unique_ptr<const ForcePasses> select_passes(const BondLaw& law, DampingKind damping);

}  // namespace frac::rubber
