#pragma once
// Shared by the rubber unit tests: the bond law in natural units (Δ = m = a = 1, b given), with the
// short-bond width us, the cut-off uc and its width w; evaluators and the three-body weight chosen by name
// (defaults: the paper's); and the positions of a model's lattice under a homogeneous deformation F.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "continuum/mooney_rivlin.hpp"
#include "rubber/bond_law.hpp"
#include "rubber/model.hpp"

namespace frac::rubber::test {

inline BondLaw natural_law(double b, double us, double uc, double w, const char* pair = "marder",
                           const char* cutoff = "fermi", const char* angle = "marder", const char* weight = "pair") {
  LawParams p;
  p.spacing = 1;
  p.A = frac::mr::lattice_A(1, 1, 1);
  p.B = frac::mr::lattice_B(1, 1, b, 1);
  p.short_width = us;
  p.cutoff = uc;
  p.cutoff_width = w;
  return make_bond_law(p, pair, cutoff, angle, weight);
}

// q = F·r for every node (layout [x.., y..]).
inline std::vector<double> deformed(const Model& model, const Eigen::Matrix2d& F) {
  const Lattice& L = model.lattice();
  std::vector<double> q(2 * L.n);
  for (std::size_t i = 0; i < L.n; ++i) {
    const Eigen::Vector2d x = F * Eigen::Vector2d(L.rx[i], L.ry[i]);
    q[i] = x.x();
    q[L.n + i] = x.y();
  }
  return q;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Largest difference between the forces at q and minus the central differences (step 1e-6 in the units
// of q) of the potential energy, over the largest force.
inline double fd_error(Model& model, std::vector<double> q) {
  std::vector<double> f(q.size());
  model.forces(q, f);
  const double eps = 1e-6;
  double worst = 0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const double q0 = q[k];
    q[k] = q0 + eps;
    const double up = model.potential_energy(q).total();
    q[k] = q0 - eps;
    const double um = model.potential_energy(q).total();
    q[k] = q0;
    worst = std::max(worst, std::abs(-(up - um) / (2 * eps) - f[k]));
  }
  return worst / max_abs(f);
}

}  // namespace frac::rubber::test
