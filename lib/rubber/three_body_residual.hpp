#pragma once
// The three-body residual (not in the paper; a lever for running cracks, law.three_body_residual = κ):
// a pair (s, t) of node i's slots whose bonds fail keeps the constant fraction κ of its far-field
// three-body energy, as Marder's pair term keeps the constant f(u_c) past u_c:
//
//   E_i = Σ_s f(u_is) + Σ_{s≠t} [h_s h_t (g(a_s·a_t) − c_st) + c_st],   c_st = κ g(Δ² (F d_s)·(F d_t)),
//
// d_s the reference direction of slot s and F the scene's far-field stretch. Where h = 1 (the far field,
// u_c ≥ u_0 + 15 widths) the energy and forces are the paper's: the far field stays Mooney-Rivlin. In the
// cut-off the cohesive force −(g − c) ∇(h_s h_t) is (1 − κ) of the paper's for far-field pairs: a bond that
// fails releases (1 − κ) of the three-body share it held (rubber-lattice-validation.md §D.2: ≈ 31 m a per
// crossing bond at (1.2, 3)), the barrier that holds a static or driven tip (docs/rubber-run.md). The
// constant Σ c_st over a node's existing slots is added to its energy, so the total energy of a
// homogeneous state is unchanged.
#include <vector>

#include <Eigen/Core>

#include "rubber/bond_law.hpp"
#include "rubber/lattice.hpp"

namespace frac::rubber {

// c_st for s, t = 0..5 (row-major 6 × 6, zero on the diagonal), J; κ in [0, 1).
std::vector<double> three_body_residual(const BondLaw& law, const Lattice& lattice, const Eigen::Matrix2d& F,
                                        double kappa);

}  // namespace frac::rubber
