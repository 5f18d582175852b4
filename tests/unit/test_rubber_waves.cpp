// Waves in the rubber lattice against the Mooney-Rivlin continuum (physics/rubber-lattice.md §4,
// rubber-lattice-validation.md §2.A.5 and §D.1): long-wave longitudinal and shear speeds along x and y
// at (λx, λy) = (1.2, 3), (1.5, 3), (2, 2), measured by integrating standing waves on small periodic
// lattices (wavelengths 64Δ and 32Δ, extrapolated to k → 0), and by the static mode probe; the far
// field stiffened by a cut-off too close to the bond length; the unstable lattice when a bond family
// is shorter than Δ + u_s. Units: m = Δ = a = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "continuum/mooney_rivlin.hpp"
#include "dynamics/integrator.hpp"
#include "rubber/probe.hpp"
#include "rubber_test_support.hpp"

namespace {

namespace mr = frac::mr;

using namespace frac::rubber;
using Eigen::Matrix2d;
using Eigen::Vector2d;

using test::natural_law;

// ω of the standing wave x_i += ε U cos(k·r_i) on the patch, from the first zero of its amplitude
// (a quarter period), integrated with velocity Verlet.
double standing_wave_omega(Patch& patch, const Vector2d& k_ref, const Vector2d& U, double omega_guess) {
  Model& model = *patch.model;
  const Lattice& L = model.lattice();
  const std::size_t n = L.n;
  std::vector<double> shape(2 * n), q(patch.q), v(2 * n, 0.0);
  double norm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double c = std::cos(k_ref.x() * L.rx[i] + k_ref.y() * L.ry[i]);
    shape[i] = U.x() * c;
    shape[n + i] = U.y() * c;
  }
  for (double s : shape) norm += s * s;
  const double eps = 1e-6;
  for (std::size_t k = 0; k < 2 * n; ++k) q[k] += eps * shape[k];
  // 200 steps a period, and well inside the stability bound of the lattice (dt < 2/ω_max, ω_max ≈ 20).
  const double dt = std::min(0.005 * 2 * std::numbers::pi / omega_guess, 0.02);
  frac::dynamics::VelocityVerlet verlet;
  verlet.start(model, 0, dt, q, v);
  auto amplitude = [&] {
    double a = 0;
    for (std::size_t k = 0; k < 2 * n; ++k) a += shape[k] * (verlet.q()[k] - patch.q[k]);
    return a / (eps * norm);
  };
  double prev = amplitude(), t_prev = 0;
  for (int s = 0; s < 100000; ++s) {
    verlet.step(model);
    const double a = amplitude();
    if (a <= 0) {
      const double t0 = t_prev + dt * prev / (prev - a);
      return std::numbers::pi / (2 * t0);
    }
    prev = a;
    t_prev = verlet.t();
  }
  return 0;
}

struct Case {
  double lx, ly;
  char dir;
};

TEST(RubberWaves, StandingWavesMatchMooneyRivlinSpeeds) {
  const double b = 1.5;
  const BondLaw law = natural_law(b, 0.1, 100, 0.1);  // every bond in branch 2, h = 1
  double worst = 0;
  for (const Case c :
       {Case{1.2, 3, 'x'}, Case{1.2, 3, 'y'}, Case{1.5, 3, 'x'}, Case{1.5, 3, 'y'}, Case{2, 2, 'x'}, Case{2, 2, 'y'}}) {
    const bool along_x = c.dir == 'x';
    // Box 64Δ long in the direction of propagation (rows along x: 64 nodes along x, or 74 rows ≈ 64.1Δ along y).
    const std::int64_t nx = along_x ? 64 : 4, ny = along_x ? 4 : 74;
    Patch patch = make_patch(law, 1, nx, ny, true, Matrix2d{{c.lx, 0}, {0, c.ly}});
    const double box = along_x ? 64.0 : 74 * std::sqrt(3.0) / 2;
    const Vector2d e_along = along_x ? Vector2d(1, 0) : Vector2d(0, 1);
    const Vector2d e_across = along_x ? Vector2d(0, 1) : Vector2d(1, 0);
    const mr::Speeds want = along_x ? mr::speeds_x(c.lx, c.ly, 1, b) : mr::speeds_y(c.lx, c.ly, 1, b);
    const double stretch = along_x ? c.lx : c.ly;
    double got[2];
    for (int pol = 0; pol < 2; ++pol) {
      const Vector2d U = pol == 0 ? e_across : e_along;
      const double c_ref = (pol == 0 ? want.transverse : want.longitudinal) / stretch;
      double c2[2];
      for (int m = 1; m <= 2; ++m) {
        const double k = 2 * std::numbers::pi * m / box;
        const double w = standing_wave_omega(patch, k * e_along, U, c_ref * k);
        c2[m - 1] = (w / k) * (w / k);
        // The static probe gives the same ω².
        const double w2 = mode_omega2(patch, k * e_along, U);
        EXPECT_NEAR(w * w, w2, 1e-3 * w2);
      }
      got[pol] = stretch * std::sqrt((4 * c2[0] - c2[1]) / 3);
    }
    const double et = got[0] / want.transverse - 1, el = got[1] / want.longitudinal - 1;
    worst = std::max({worst, std::abs(et), std::abs(el)});
    std::cout << "[measured] (" << c.lx << ", " << c.ly << ") along " << c.dir << ": c_T " << got[0] << " (MR "
              << want.transverse << ", " << 100 * et << "%), c_L " << got[1] << " (MR " << want.longitudinal << ", "
              << 100 * el << "%)\n";
    EXPECT_LT(std::abs(et), 0.02);
    EXPECT_LT(std::abs(el), 0.02);
  }
  std::cout << "[measured] worst relative wave-speed error: " << worst << "\n";
}

TEST(RubberWaves, StaticProbeMatchesMooneyRivlinInBothOrientations) {
  const double b = 1.5;
  const BondLaw law = natural_law(b, 0.1, 100, 0.1);
  for (const bool rows_x : {true, false})
    for (const Case c : {Case{1.2, 3, 'x'}, Case{1.2, 3, 'y'}, Case{1.5, 3, 'x'}, Case{2, 2, 'y'}}) {
      const LatticeSpeeds s = lattice_speeds(law, 1, c.lx, c.ly, c.dir, rows_x);
      const mr::Speeds want = c.dir == 'x' ? mr::speeds_x(c.lx, c.ly, 1, b) : mr::speeds_y(c.lx, c.ly, 1, b);
      EXPECT_NEAR(s.transverse, want.transverse, 2e-3 * want.transverse) << c.lx << " " << c.ly << " " << c.dir;
      EXPECT_NEAR(s.longitudinal, want.longitudinal, 2e-3 * want.longitudinal) << c.lx << " " << c.ly << " " << c.dir;
    }
}

// §D.1 of the validation note: at (1.2, 3), b = 1.5, width 0.05, the bonds across x have u_0 = 2.666;
// with u_c = u_0 + 15 widths the far field is Mooney-Rivlin within 2%, with u_c = u_0 + 6 widths c_T is
// several times too large.
TEST(RubberWaves, CutoffCloseToTheBondLengthStiffensTheFarField) {
  const double b = 1.5, w = 0.05;
  const double u0 = std::hypot(0.5 * 1.2, std::sqrt(3.0) / 2 * 3);
  const mr::Speeds want = mr::speeds_x(1.2, 3, 1, b);
  const LatticeSpeeds far = lattice_speeds(natural_law(b, 0.1, u0 + 15 * w, w), 1, 1.2, 3, 'x');
  const LatticeSpeeds near = lattice_speeds(natural_law(b, 0.1, u0 + 6 * w, w), 1, 1.2, 3, 'x');
  std::cout << "[measured] (1.2, 3) along x, width 0.05: u_c = u0 + 15w: c_T " << far.transverse << " c_L "
            << far.longitudinal << "; u_c = u0 + 6w: c_T " << near.transverse << " c_L " << near.longitudinal << " (MR "
            << want.transverse << ", " << want.longitudinal << ")\n";
  EXPECT_NEAR(far.transverse, want.transverse, 0.02 * want.transverse);
  EXPECT_NEAR(far.longitudinal, want.longitudinal, 0.02 * want.longitudinal);
  EXPECT_GT(near.transverse, 3 * want.transverse);
}

// The three-body weight all_bonds leaves the far field Mooney-Rivlin: at u_c = u_0 + 15 widths (Fermi,
// the Fermi tail of W) and with the compact smoothstep cut-off the lattice's long-wave speeds along x
// and y at (1.2, 3) are those of the paper's weight.
TEST(RubberWaves, AllBondsWeightKeepsTheFarFieldSpeeds) {
  const double b = 1.5, w = 0.05;
  const double u0 = std::hypot(0.5 * 1.2, std::sqrt(3.0) / 2 * 3);
  for (const char dir : {'x', 'y'}) {
    const mr::Speeds want = dir == 'x' ? mr::speeds_x(1.2, 3, 1, b) : mr::speeds_y(1.2, 3, 1, b);
    const LatticeSpeeds paper = lattice_speeds(natural_law(b, 0.1, u0 + 15 * w, w), 1, 1.2, 3, dir);
    const LatticeSpeeds fermi =
        lattice_speeds(natural_law(b, 0.1, u0 + 15 * w, w, "marder", "fermi", "marder", "all_bonds"), 1, 1.2, 3, dir);
    const LatticeSpeeds soft = lattice_speeds(
        natural_law(b, 0.1, u0 + 0.12, 0.1, "marder-soft", "smoothstep", "marder", "all_bonds"), 1, 1.2, 3, dir);
    std::cout << "[measured] (1.2, 3) along " << dir << ", all_bonds: fermi u0 + 15w c_T " << fermi.transverse
              << " c_L " << fermi.longitudinal << " (pair weight " << paper.transverse << ", " << paper.longitudinal
              << "); smoothstep c_T " << soft.transverse << " c_L " << soft.longitudinal << " (MR " << want.transverse
              << ", " << want.longitudinal << ")\n";
    EXPECT_NEAR(fermi.transverse, want.transverse, 0.02 * want.transverse);
    EXPECT_NEAR(fermi.longitudinal, want.longitudinal, 0.02 * want.longitudinal);
    EXPECT_NEAR(soft.transverse, want.transverse, 2e-3 * want.transverse);
    EXPECT_NEAR(soft.longitudinal, want.longitudinal, 2e-3 * want.longitudinal);
  }
}

// A bond family shorter than Δ + u_s (λx = 1 with rows along x): not Mooney-Rivlin; the transverse mode
// along x is unstable (ω² < 0), and the probe says so with NaN.
TEST(RubberWaves, BranchOneFamilyIsNotMooneyRivlin) {
  const LatticeSpeeds s = lattice_speeds(natural_law(1.5, 0.1, 100, 0.1), 1, 1.0, 3, 'x');
  EXPECT_LT(s.transverse_omega2, 0);
  EXPECT_TRUE(std::isnan(s.transverse));
  // Rows along y keep every bond longer than Δ + u_s at (1, 3): Mooney-Rivlin again.
  const LatticeSpeeds t = lattice_speeds(natural_law(1.5, 0.1, 100, 0.1), 1, 1.0, 3, 'x', false);
  const mr::Speeds want = mr::speeds_x(1.0, 3, 1, 1.5);
  EXPECT_NEAR(t.transverse, want.transverse, 0.02 * want.transverse);
}

TEST(RubberWaves, OmegaMaxOfTheNote) {
  // rubber-lattice.md §5: ω_max ≈ 8.5 (reference, u_s = 0.1), 13.8 at (1.2, 3), b = 1.5.
  const double ref = omega_max(natural_law(1.5, 0.1, 100, 0.1), 1, Matrix2d::Identity());
  const double stretched = omega_max(natural_law(1.5, 0.1, 100, 0.1), 1, Matrix2d{{1.2, 0}, {0, 3}});
  std::cout << "[measured] omega_max: " << ref << " at (1, 1), " << stretched << " at (1.2, 3)\n";
  EXPECT_NEAR(ref, 8.5, 0.3);
  EXPECT_NEAR(stretched, 13.8, 0.3);
}

}  // namespace
