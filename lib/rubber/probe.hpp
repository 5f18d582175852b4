#pragma once
// Probes of the lattice itself, on small periodic patches held at a homogeneous deformation F:
//   - long-wave speeds: the restoring force of an imposed long-wave mode gives ω² exactly (a linear,
//     pure mode: along x and y the stretched lattice keeps its mirror lines, so the modes are purely
//     longitudinal and transverse); two wavelengths, extrapolated to k → 0 (c² = c0² + αk² + O(k⁴));
//   - ω_max: the largest frequency of the patch's normal modes (dense Hessian by central differences
//     of the forces, 12 × 12 patch, which samples the zone edge and the zone corners).
// rubber-run uses them to warn when the cut-off stiffens the far field (rubber-lattice-validation.md
// §D.1) and to bound the time step (rubber-lattice.md §5); the tests use them to check the continuum
// limit of the waves.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "rubber/bond_law.hpp"
#include "rubber/model.hpp"

namespace frac::rubber {

// A periodic patch of nx × ny nodes (spacing from the law) deformed homogeneously by F; positions in q.
struct Patch {
  std::unique_ptr<Model> model;
  std::vector<double> q;  // x then y, deformed by F
  Eigen::Matrix2d F;
};
Patch make_patch(const BondLaw& law, double node_mass, std::int64_t nx, std::int64_t ny, bool rows_along_x,
                 const Eigen::Matrix2d& F);

// ω² (reference wavevector k_ref, polarization U in the lab frame) of the mode x_i += ε U cos(k·r_i) on
// a patch whose box admits k_ref.
double mode_omega2(Patch& patch, const Eigen::Vector2d& k_ref, const Eigen::Vector2d& U);

struct LatticeSpeeds {
  double transverse = 0, longitudinal = 0;                // m/s, lab frame; NaN when ω² < 0 (the mode is unstable)
  double transverse_omega2 = 0, longitudinal_omega2 = 0;  // ω² at the longest wavelength (k = 2π/L)
  double wavelength = 0;                                  // m: reference length of the longest wave probed
};
// Long-wave lab speeds along 'x' or 'y' at F = diag(lx, ly), from waves of reference length L and L/2
// (L = `wavelengths` lattice spacings, default 128), extrapolated to k → 0.
LatticeSpeeds lattice_speeds(const BondLaw& law, double node_mass, double lx, double ly, char direction,
                             bool rows_along_x = true, double wavelengths = 128);

// Largest normal-mode frequency (rad/s) of a 12 × 12 periodic patch at F.
double omega_max(const BondLaw& law, double node_mass, const Eigen::Matrix2d& F, bool rows_along_x = true);

}  // namespace frac::rubber
