// Rubber lattice: the bond-law evaluators, the continuum limit (energy and Piola stress of the
// Mooney-Rivlin sheet), forces against finite differences of the energy, the moment form of the
// three-body sum against the pair loop, and bit-identical results for any number of threads
// (physics/rubber-lattice.md §2-3, rubber-lattice-validation.md §2.A).
// Units in these tests: m = Δ = a = 1 (the code is unit-agnostic).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>

#include "continuum/mooney_rivlin.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/bond_law.hpp"
#include "rubber/lattice.hpp"
#include "rubber/model.hpp"
#include "rubber/probe.hpp"
#include "rubber_test_support.hpp"

namespace {

namespace mr = frac::mr;

using namespace frac::rubber;
using Eigen::Matrix2d;
using Eigen::Vector2d;

using test::deformed;
using test::fd_error;
using test::max_abs;
using test::natural_law;

std::unique_ptr<Model> make_model(const BondLaw& law, std::int64_t nx, std::int64_t ny, bool rows_x, double notch,
                                  bool periodic, int threads = 1, DampingKind damping = DampingKind::none,
                                  double beta = 0) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = law.params.spacing;
  o.rows_along = rows_x ? "x" : "y";
  o.notch = notch;
  ModelOptions mo;
  mo.law = law;
  mo.node_mass = 1;
  mo.threads = threads;
  mo.damping = damping;
  mo.beta = beta;
  return std::make_unique<Model>(build_lattice(frac::mesh::make_triangular_lattice(o), periodic, periodic), mo);
}

double shortest_family(const Matrix2d& F) {
  double u = 1e300;
  for (int s = 0; s < 3; ++s) {
    const double th = s * std::numbers::pi / 3;
    u = std::min(u, (F * Vector2d(std::cos(th), std::sin(th))).norm());
    const double th2 = th + std::numbers::pi / 6;
    u = std::min(u, (F * Vector2d(std::cos(th2), std::sin(th2))).norm());
  }
  return u;
}

// Random F = R(θ) diag(l1, l2) R(φ)ᵀ with l in [lo, hi].
Matrix2d random_F(frac::Rng& rng, double lo, double hi) {
  auto rot = [](double t) { return Matrix2d{{std::cos(t), -std::sin(t)}, {std::sin(t), std::cos(t)}}; };
  const double l1 = rng.uniform(lo, hi), l2 = rng.uniform(lo, hi);
  return rot(rng.uniform(0, 2 * std::numbers::pi)) * Matrix2d{{l1, 0}, {0, l2}} *
         rot(rng.uniform(0, 2 * std::numbers::pi)).transpose();
}

// ------------------------------------------------------------------------------------------ evaluators
TEST(RubberLaw, PairBranchesJoinAndDerivativesMatch) {
  const BondLaw law = natural_law(1.5, 0.1, 3.0, 0.05);
  const LawParams& p = law.params;
  const PairMarder f(p);
  const PairMarderC1 f1(p);
  const double knee = p.spacing + p.short_width, e = 1e-9;
  // Continuous at Δ + u_s and at u_c; the slope drops by (A/6)(2Δ + u_s) for the paper's f, not for C¹.
  EXPECT_NEAR(f(knee - e, 3).v, f(knee + e, 3).v, 1e-7);
  EXPECT_NEAR(f(knee - e, 3).d - f(knee + e, 3).d, p.A / 6 * (2 * p.spacing + p.short_width), 1e-6);
  EXPECT_NEAR(f1(knee - e, 3).v, f1(knee + e, 3).v, 1e-7);
  EXPECT_NEAR(f1(knee + e, 3).d - f1(knee - e, 3).d, 0.0, 1e-6);
  EXPECT_NEAR(f(3 - e, 3).v, f(3 + e, 3).v, 1e-6);
  EXPECT_EQ(f(3.5, 3).d, 0.0);
  // Stress-free bonds at Δ, zero energy of the reference node (6 K0 − 4BΔ⁴ = 0 with h = 1).
  EXPECT_NEAR(f(1.0, 3).d, 0.0, 1e-15);
  EXPECT_NEAR(f1(1.0, 3).d, 0.0, 1e-15);
  EXPECT_NEAR(6 * f(1.0, 3).v - 4 * p.B, 0.0, 1e-14);
  // Derivatives against central differences away from the kinks.
  const CutoffFermi h(p);
  const AngleMarder g(p);
  for (double u : {0.5, 0.9, 1.05, 1.3, 2.0, 2.9, 2.99, 3.05}) {
    const double d = 1e-6;
    EXPECT_NEAR(f(u, 3).d, (f(u + d, 3).v - f(u - d, 3).v) / (2 * d), 1e-6 * (1 + std::abs(f(u, 3).d))) << u;
    EXPECT_NEAR(f1(u, 3).d, (f1(u + d, 3).v - f1(u - d, 3).v) / (2 * d), 1e-6 * (1 + std::abs(f1(u, 3).d))) << u;
    EXPECT_NEAR(h(u, 3).d, (h(u + d, 3).v - h(u - d, 3).v) / (2 * d), 1e-6 * (1 + std::abs(h(u, 3).d))) << u;
  }
  const PairMarderSoft fs(p);  // the paper's f below 2.95, f(2.95) beyond 3, smooth between
  EXPECT_EQ(fs(2.9, 3).v, f(2.9, 3).v);
  EXPECT_EQ(fs(2.9, 3).d, f(2.9, 3).d);
  EXPECT_DOUBLE_EQ(fs(3.2, 3).v, f(2.95, 3).v);
  EXPECT_EQ(fs(3.2, 3).d, 0.0);
  for (double u : {2.951, 2.96, 2.975, 2.99, 2.999}) {
    const double d = 1e-7;
    EXPECT_NEAR(fs(u, 3).d, (fs(u + d, 3).v - fs(u - d, 3).v) / (2 * d), 1e-5 * (1 + std::abs(fs(u, 3).d))) << u;
  }
  const CutoffSmoothstep hs(p);  // L = 0.05: h = 1 below 2.95, 0 above 3
  EXPECT_EQ(hs(2.95, 3).v, 1.0);
  EXPECT_EQ(hs(2.9, 3).d, 0.0);
  EXPECT_EQ(hs(3.0, 3).v, 0.0);
  EXPECT_NEAR(hs(2.975, 3).v, 0.5, 1e-14);
  for (double u : {2.951, 2.96, 2.975, 2.99, 2.999}) {
    const double d = 1e-7;
    EXPECT_NEAR(hs(u, 3).d, (hs(u + d, 3).v - hs(u - d, 3).v) / (2 * d), 1e-5 * (1 + std::abs(hs(u, 3).d))) << u;
  }
  for (double X : {-3.0, -0.5, 0.0, 0.5, 4.0}) {
    EXPECT_NEAR(g(X).d, (g(X + 1e-6).v - g(X - 1e-6).v) / 2e-6, 1e-6 * (1 + std::abs(g(X).d)));
    EXPECT_NEAR(g(X).v, -p.B / 27 * (X + 2) * (X + 2), 1e-13);
  }
  EXPECT_DOUBLE_EQ(h(3.0, 3.0).v, 0.5);
}

TEST(RubberLaw, UnknownLawNamesTheKeyAndTheChoices) {
  try {
    make_pair_law("hooke", LawParams{});
    FAIL();
  } catch (const frac::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("law.pair"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("marder-c1"), std::string::npos);
  }
  EXPECT_EQ(pair_law_names(), (std::vector<std::string>{"marder", "marder-c1", "marder-soft"}));
  EXPECT_EQ(cutoff_law_names(), (std::vector<std::string>{"fermi", "smoothstep", "none"}));
}

// ------------------------------------------------------------------------------------------ continuum limit
// Homogeneous deformations with every bond in branch 2 and h = 1 to round-off (u_c 100Δ away): the
// lattice energy per node is m a (J1 + b J2) and dU/dF per node is A_cell times the Piola stress of the
// note, to 1e-10 relative; forces vanish.
TEST(RubberContinuum, EnergyAndPiolaStressOfRandomHomogeneousDeformations) {
  frac::Rng rng(11);
  double worst_energy = 0, worst_stress = 0, worst_force = 0;
  for (const bool rows_x : {true, false}) {
    for (const auto& [lo, hi, us] : {std::tuple{1.02, 1.12, 0.01}, std::tuple{1.15, 3.5, 0.1}}) {
      for (int trial = 0; trial < 12; ++trial) {
        const double b = rng.uniform(0.2, 1.9);
        Matrix2d F = random_F(rng, lo, hi);
        while (shortest_family(F) < 1 + us + 1e-3) F = random_F(rng, lo, hi);
        const BondLaw law = natural_law(b, us, 100, 0.1);
        auto model = make_model(law, 6, 6, rows_x, 0, true);
        model->set_box(F);
        const auto q = deformed(*model, F);
        const double n = static_cast<double>(model->nodes());
        const double U = model->potential_energy(q).total() / n;
        const double W = mr::energy_per_mass(F, 1, b);
        worst_energy = std::max(worst_energy, std::abs(U - W) / std::abs(W));
        EXPECT_NEAR(U, W, 1e-10 * std::abs(W)) << "F = " << F << " b = " << b;

        const double cell = std::sqrt(3.0) / 2;
        const Matrix2d P = model->virial(q) * F.inverse().transpose() / (n * cell);
        const Matrix2d Pc = mr::piola(F, {1, b, 1 / cell});
        worst_stress = std::max(worst_stress, (P - Pc).cwiseAbs().maxCoeff() / Pc.norm());
        EXPECT_LT((P - Pc).cwiseAbs().maxCoeff(), 1e-10 * Pc.norm()) << "F = " << F << "\n" << P << "\n" << Pc;

        std::vector<double> f(q.size());
        model->forces(q, f);
        worst_force = std::max(worst_force, max_abs(f) / (Pc.norm() * cell));
        EXPECT_LT(max_abs(f), 1e-10 * Pc.norm()) << "F = " << F;
      }
    }
  }
  std::cout << "[measured] continuum limit: energy rel. error " << worst_energy << ", Piola rel. error " << worst_stress
            << ", residual force / stress " << worst_force << "\n";
}

TEST(RubberContinuum, KnownStressAtOnePointFiveTwoPointFive) {
  // rubber-lattice-validation.md §2.A.3: dU/dF per node = diag(7.40625, 4.84375) at (1.5, 2.5), b = 1.5.
  const BondLaw law = natural_law(1.5, 0.1, 100, 0.1);
  auto model = make_model(law, 6, 6, true, 0, true);
  const Matrix2d F{{1.5, 0}, {0, 2.5}};
  model->set_box(F);
  const auto q = deformed(*model, F);
  const Matrix2d dUdF = model->virial(q) * F.inverse().transpose() / static_cast<double>(model->nodes());
  EXPECT_NEAR(dUdF(0, 0), 7.40625, 1e-11);
  EXPECT_NEAR(dUdF(1, 1), 4.84375, 1e-11);
  EXPECT_NEAR(dUdF(0, 1), 0.0, 1e-11);
  EXPECT_NEAR(dUdF(1, 0), 0.0, 1e-11);
}

TEST(RubberContinuum, ReferenceLatticeIsStressFreeWithZeroEnergy) {
  for (const char* pair : {"marder", "marder-c1"}) {
    const BondLaw law = natural_law(1.5, 0.1, 100, 0.1, pair);
    auto model = make_model(law, 6, 6, true, 0, true);
    const auto q = deformed(*model, Matrix2d::Identity());
    EXPECT_LT(model->virial(q).cwiseAbs().maxCoeff(), 1e-12) << pair;
    EXPECT_NEAR(model->potential_energy(q).total(), 0.0, 1e-12) << pair;
  }
}

// ------------------------------------------------------------------------------------------ gradients
// Random configurations around the stretched state (1.2, 3) with bonds in all three branches of f and
// across the Fermi cut-off (u_c = 2.75, width 0.05): central differences of the energy agree with the
// forces within 1e-6 of the largest force (test::fd_error).

// Perturbs q until no intact bond sits within `gap` of a kink of f (Δ + u_s, u_c).
std::vector<double> random_near(const Model& model, const Matrix2d& F, double amplitude, frac::Rng& rng, double gap,
                                int* in_branch = nullptr) {
  const Lattice& L = model.lattice();
  const LawParams& p = model.options().law.params;
  for (;;) {
    auto q = deformed(model, F);
    for (double& x : q) x += rng.uniform(-amplitude, amplitude);
    bool ok = true;
    int branch[4] = {0, 0, 0, 0};
    for (std::size_t b = 0; b < L.bonds() - 3; ++b) {
      if (model.status(b) != 0) continue;
      const double u = model.bond_length(b, q);
      ok = ok && std::abs(u - (p.spacing + p.short_width)) > gap && std::abs(u - p.cutoff) > gap;
      ++branch[u < p.spacing + p.short_width ? 0 : u < p.cutoff - 3 * p.cutoff_width ? 1 : u < p.cutoff ? 2 : 3];
    }
    if (in_branch)
      for (int k = 0; k < 4; ++k) in_branch[k] = branch[k];
    if (ok) return q;
  }
}

TEST(RubberForces, MatchFiniteDifferencesInAllBranches) {
  frac::Rng rng(5);
  double worst = 0;
  for (const auto& [pair, cutoff, angle] :
       {std::tuple{"marder", "fermi", "marder"}, std::tuple{"marder", "fermi", "marder-pairwise"},
        std::tuple{"marder-c1", "fermi", "marder"}, std::tuple{"marder-c1", "fermi", "marder-pairwise"},
        std::tuple{"marder", "smoothstep", "marder"}, std::tuple{"marder-soft", "smoothstep", "marder"}}) {
    {
      const double width = std::string(cutoff) == "smoothstep" ? 0.2 : 0.05;
      const BondLaw law = natural_law(1.5, 0.1, 2.75, width, pair, cutoff, angle);
      for (const bool periodic : {false, true}) {
        auto model = make_model(law, periodic ? 6 : 7, 8, true, periodic ? 0 : 2.5, periodic);
        const Matrix2d F{{1.2, 0.1}, {0, 3.0}};
        model->set_box(F);
        int branch[4];
        const auto q = random_near(*model, F, 0.12, rng, 2e-4, branch);
        EXPECT_GT(branch[0], 0);  // short bonds (branch 1)
        EXPECT_GT(branch[1], 0);  // Mooney-Rivlin bonds
        EXPECT_GT(branch[2], 0);  // in the cut-off (within 3 widths of u_c)
        const double err = fd_error(*model, q);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-6) << pair << " " << cutoff << " " << angle << (periodic ? " periodic" : " notched");
      }
    }
  }
  std::cout << "[measured] forces vs central differences: worst error / max |F| = " << worst << "\n";
}

TEST(RubberForces, MomentFormEqualsPairLoop) {
  for (const char* weight : {"pair", "all_bonds"}) {
    frac::Rng rng(9);
    const BondLaw fast = natural_law(1.2, 0.1, 2.8, 0.05, "marder", "fermi", "marder", weight);
    const BondLaw slow = natural_law(1.2, 0.1, 2.8, 0.05, "marder", "fermi", "marder-pairwise", weight);
    auto a = make_model(fast, 9, 8, false, 3, false);
    auto b = make_model(slow, 9, 8, false, 3, false);
    const auto q = random_near(*a, Matrix2d{{3.0, 0}, {0.2, 1.3}}, 0.1, rng, 0);
    std::vector<double> fa(q.size()), fb(q.size());
    a->forces(q, fa);
    b->forces(q, fb);
    const double scale = max_abs(fa);
    for (std::size_t k = 0; k < q.size(); ++k) EXPECT_NEAR(fa[k], fb[k], 1e-12 * scale) << weight;
    const double ea = a->potential_energy(q).three_body, eb = b->potential_energy(q).three_body;
    EXPECT_NEAR(ea, eb, 1e-12 * std::abs(eb)) << weight;
  }
}

TEST(RubberForces, SumToZeroAndVirialIsSymmetric) {
  frac::Rng rng(3);
  const BondLaw law = natural_law(1.5, 0.1, 2.75, 0.05);
  auto model = make_model(law, 10, 10, true, 4, false);
  const auto q = random_near(*model, Matrix2d{{1.2, 0}, {0, 3}}, 0.15, rng, 0);
  std::vector<double> f(q.size());
  model->forces(q, f);
  double sx = 0, sy = 0;
  const std::size_t n = model->nodes();
  for (std::size_t i = 0; i < n; ++i) {
    sx += f[i];
    sy += f[n + i];
  }
  EXPECT_LT(std::abs(sx) + std::abs(sy), 1e-12 * max_abs(f) * static_cast<double>(n));
  const Matrix2d w = model->virial(q);
  EXPECT_NEAR(w(0, 1), w(1, 0), 1e-12 * w.norm());
}

// ------------------------------------------------------------------------------------------ weight
// law.three_body_weight = all_bonds (bond_law.hpp): node i's three-body term times W_i = Π_s h(u_is).
// The forces carry the derivative of W: central differences agree within 1e-6 of max |F|, with bonds in
// the cut-off, free edges (W = 0 there) and periodic, for both forms of the three-body sum.
TEST(RubberForces, AllBondsWeightMatchesFiniteDifferences) {
  frac::Rng rng(17);
  double worst = 0;
  for (const auto& [pair, cutoff, angle] :
       {std::tuple{"marder", "fermi", "marder"}, std::tuple{"marder", "fermi", "marder-pairwise"},
        std::tuple{"marder-c1", "fermi", "marder"}, std::tuple{"marder-soft", "smoothstep", "marder"},
        std::tuple{"marder-soft", "smoothstep", "marder-pairwise"}}) {
    const double width = std::string(cutoff) == "smoothstep" ? 0.2 : 0.05;
    const BondLaw law = natural_law(1.5, 0.1, 2.75, width, pair, cutoff, angle, "all_bonds");
    const BondLaw paper = natural_law(1.5, 0.1, 2.75, width, pair, cutoff, angle);
    for (const bool periodic : {false, true}) {
      auto model = make_model(law, periodic ? 6 : 7, 8, true, periodic ? 0 : 2.5, periodic);
      auto reference = make_model(paper, periodic ? 6 : 7, 8, true, periodic ? 0 : 2.5, periodic);
      const Matrix2d F{{1.2, 0.1}, {0, 3.0}};
      model->set_box(F);
      reference->set_box(F);
      int branch[4];
      const auto q = random_near(*model, F, 0.12, rng, 2e-4, branch);
      EXPECT_GT(branch[2], 0);  // bonds in the cut-off: 0 < W < 1 somewhere
      const double err = fd_error(*model, q);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << pair << " " << cutoff << " " << angle << (periodic ? " periodic" : " notched");
      // The weight is active: the three-body energy differs from the paper's.
      EXPECT_GT(std::abs(model->potential_energy(q).three_body - reference->potential_energy(q).three_body), 1e-3);
    }
  }
  std::cout << "[measured] all_bonds weight, forces vs central differences: worst error / max |F| = " << worst << "\n";
}

// Far field: complete shells, bonds far below u_c: W = 1, exactly with the compact smoothstep cut-off
// (forces and energy equal the paper's), up to the Fermi tail at u_c = u_0 + 15 widths: W = 1 − O(6e^{-15})
// in the energy, and T h'/u ~ T e^{-15}/w in the forces (measured 1.3e-6 of the three-body energy and
// 5e-4 of the largest force of a configuration perturbed by ±0.02Δ; wave speeds: RubberWaves).
TEST(RubberForces, AllBondsWeightIsOneInTheFarField) {
  frac::Rng rng(23);
  const Matrix2d F{{1.2, 0}, {0, 3}};
  const double u0 = std::hypot(0.5 * 1.2, std::sqrt(3.0) / 2 * 3);
  struct Law {
    const char *pair, *cutoff;
    double uc, w, force_tol, energy_tol;
  };
  for (const Law& l : {Law{"marder-soft", "smoothstep", u0 + 0.3, 0.1, 1e-14, 1e-14},
                       Law{"marder", "fermi", u0 + 0.75, 0.05, 2e-3, 1e-5}}) {
    auto a = make_model(natural_law(1.5, 0.1, l.uc, l.w, l.pair, l.cutoff, "marder", "all_bonds"), 8, 8, true, 0, true);
    auto b = make_model(natural_law(1.5, 0.1, l.uc, l.w, l.pair, l.cutoff), 8, 8, true, 0, true);
    a->set_box(F);
    b->set_box(F);
    const auto q = random_near(*a, F, 0.02, rng, 0);
    std::vector<double> fa(q.size()), fb(q.size());
    a->forces(q, fa);
    b->forces(q, fb);
    double df = 0;
    for (std::size_t k = 0; k < q.size(); ++k) df = std::max(df, std::abs(fa[k] - fb[k]));
    const double ea = a->potential_energy(q).three_body, eb = b->potential_energy(q).three_body;
    std::cout << "[measured] far field (1.2, 3), " << l.cutoff
              << ": all_bonds vs pair, max |dF| / max |F| = " << df / max_abs(fb) << ", three-body energy "
              << std::abs(ea - eb) / std::abs(eb) << "\n";
    EXPECT_LE(df, l.force_tol * max_abs(fb)) << l.cutoff;
    EXPECT_LE(std::abs(ea - eb), l.energy_tol * std::abs(eb)) << l.cutoff;
  }
}

// The free edges of the unstretched sheet: with the paper's weight they feel the incomplete three-body
// sum (1.08 m a/Δ outwards, b = 1.5); with all_bonds their nodes carry the pair law alone, f'(Δ) = 0, and
// full shells at F = I exert no three-body force: the whole notched sheet is force-free.
TEST(RubberForces, AllBondsWeightMakesFreeEdgesForceFree) {
  auto a =
      make_model(natural_law(1.5, 0.1, 3.5, 0.05, "marder", "fermi", "marder", "all_bonds"), 12, 10, true, 4, false);
  auto b = make_model(natural_law(1.5, 0.1, 3.5, 0.05), 12, 10, true, 4, false);
  const auto q = deformed(*a, Matrix2d::Identity());
  std::vector<double> fa(q.size()), fb(q.size());
  a->forces(q, fa);
  b->forces(q, fb);
  std::cout << "[measured] unstretched notched sheet, largest force: pair " << max_abs(fb) << ", all_bonds "
            << max_abs(fa) << "\n";
  EXPECT_GT(max_abs(fb), 1.0);
  EXPECT_LT(max_abs(fa), 1e-12);
}

// ------------------------------------------------------------------------------------------ threads
TEST(RubberForces, BitIdenticalForAnyNumberOfThreadsAndBothSchedules) {
  // The three-pass schedule on one thread is the reference; the row-fused schedule on 1, 2, 3 and 5
  // threads must give the same bits, for both lattice orientations, periodic or with a notch.
  frac::Rng rng(21);
  const BondLaw law = natural_law(1.5, 0.1, 2.75, 0.05);
  int cases = 0;
  for (const bool rows_x : {true, false})
    for (const bool periodic : {false, true}) {
      std::vector<double> q, v, reference, a;
      double e_reference = 0;
      for (int threads : {1, 1, 2, 3, 5}) {
        const bool fused = !reference.empty();
        frac::mesh::TriangularLatticeOptions o;
        o.nx = 40;
        o.ny = 36;
        o.spacing = 1;
        o.rows_along = rows_x ? "x" : "y";
        o.notch = periodic ? 0 : 10;
        ModelOptions mo;
        mo.law = law;
        mo.threads = threads;
        mo.damping = DampingKind::uniform;
        mo.beta = 0.3;
        mo.fused = fused;
        Model model(build_lattice(frac::mesh::make_triangular_lattice(o), periodic, periodic), mo);
        EXPECT_EQ(model.fused(), fused);
        const Matrix2d F = rows_x ? Matrix2d{{1.2, 0}, {0, 3}} : Matrix2d{{3, 0}, {0, 1.2}};
        model.set_box(F);
        if (q.empty()) {
          q = random_near(model, F, 0.15, rng, 0);
          v.resize(q.size());
          for (std::size_t k = 0; k < v.size(); ++k) v[k] = std::sin(0.37 * static_cast<double>(k));
        }
        a.assign(q.size(), 0.0);
        model.accelerations(0, q, v, a);
        const double e = model.potential_energy(q).total();
        if (!fused) {
          reference = a;
          e_reference = e;
          continue;
        }
        ++cases;
        EXPECT_EQ(0, std::memcmp(reference.data(), a.data(), a.size() * sizeof(double)))
            << (rows_x ? "rows x" : "rows y") << (periodic ? " periodic" : "") << ", " << threads << " threads";
        EXPECT_EQ(0, std::memcmp(&e_reference, &e, sizeof(double)));
      }
    }
  EXPECT_EQ(cases, 16);
}

}  // namespace
