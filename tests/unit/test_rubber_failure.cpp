// Energy-neutral failure (law.failure = freeze; lib/rubber/model.hpp) and the crack path (crack.path_cutoff_ratio;
// lib/rubber/crack.hpp). A bond that passes u_c fails for good and the three-body terms that contain it are
// frozen at their value at the crossing: the energy is continuous through a failure, the forces are minus
// its gradient before and after (the failed bond exerts nothing), a run conserves the total energy through
// failures to an error that shrinks with the step, and until the first failure the law is the paper's bit
// for bit (so the far field, the continuum limit and the waves are unchanged). The crack path gives the
// bonds across the crack line the cut-off u_c and the rest ratio × u_c.
// Units: m = Δ = a = 1 for the models built here; SI (Δ = 1 mm, √a = 40 m/s) for the scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "core/scene.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/lattice.hpp"
#include "rubber/model.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"
#include "rubber/three_body_residual.hpp"
#include "rubber_test_support.hpp"

namespace {

using namespace frac::rubber;
using Eigen::Matrix2d;
using test::deformed;
using test::fd_error;
using test::max_abs;
using test::natural_law;

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

Lattice periodic_lattice(std::int64_t nx, std::int64_t ny) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = 1;
  return build_lattice(frac::mesh::make_triangular_lattice(o), true, true);
}

ModelOptions options(const BondLaw& law, Failure failure) {
  ModelOptions mo;
  mo.law = law;
  mo.failure = failure;
  return mo;
}

// ------------------------------------------------------------------------------------------ the frozen value
// One bond fails during a step from q0 to q1 (every node moved on a straight line): the energy after the
// failure is that of the lattice without the bond at q1 plus what the bond's pair and three-body terms
// held at the point of the step where it crossed u_c (found here by bisection on the straight path):
// U(q1) = U_removed(q1) + U_intact(q*) − U_removed(q*). Round-off of sums of ~200 m a: 1e-10.
TEST(RubberFailure, FrozenTermsHoldTheirValueAtTheCrossing) {
  const Lattice L = periodic_lattice(6, 6);
  const Matrix2d F{{1.2, 0}, {0, 3.0}};
  const std::size_t failing = 3 * 14 + 1;  // node 14's bond at 60°, 2.63Δ long at q0
  const double uc = 2.9;
  for (const auto& [cutoff, weight] :
       {std::tuple{"none", "pair"}, std::tuple{"fermi", "pair"}, std::tuple{"fermi", "all_bonds"}}) {
    const BondLaw law = natural_law(1.5, 0.1, 4.0, 0.05, "marder", cutoff, "marder", weight);
    Model model(L, options(law, Failure::freeze)), intact(L, options(law, Failure::paper)),
        removed(L, options(law, Failure::paper));
    for (Model* m : {&model, &intact, &removed}) {
      m->set_box(F);
      m->set_cutoff(failing, uc);  // the others at 4Δ: only this bond fails
    }
    removed.remove_bond(failing);
    auto q0 = deformed(model, F);
    frac::Rng rng(4);
    for (double& x : q0) x += rng.uniform(-0.05, 0.05);
    auto q1 = q0;
    for (double& x : q1) x += rng.uniform(-0.02, 0.02);
    const std::size_t n = model.nodes(), j = L.bond_other(failing);
    const double ux = q0[j] - q0[14], uy = q0[n + j] - q0[n + 14], u = std::hypot(ux, uy);
    q1[j] += 0.35 * ux / u;  // the bond's far end moves out along it, past u_c
    q1[n + j] += 0.35 * uy / u;
    std::vector<double> v(q0.size(), 0.0), a(q0.size());
    model.accelerations(0, q0, v, a);
    ASSERT_EQ(model.pending_breaks(), 0);
    model.accelerations(0, q1, v, a);
    ASSERT_EQ(model.pending_breaks(), 1) << cutoff;
    double lo = 0, hi = 1;
    std::vector<double> qs(q0.size());
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      for (std::size_t k = 0; k < qs.size(); ++k) qs[k] = q0[k] + mid * (q1[k] - q0[k]);
      (intact.bond_length(failing, qs) < uc ? lo : hi) = mid;
    }
    const double expected = removed.potential_energy(q1).total() + intact.potential_energy(qs).total() -
                            removed.potential_energy(qs).total();
    const Model::Energy got = model.potential_energy(q1);
    EXPECT_NEAR(got.total(), expected, 1e-10 * std::abs(expected)) << cutoff << " " << weight;
    EXPECT_LT(got.frozen, -1.0) << cutoff;  // the frozen three-body share is negative and large (m a units)
    // The failed bond exerts nothing: forces are those of the lattice without it, bit for bit.
    std::vector<double> f(q1.size()), fr(q1.size());
    model.forces(q1, f);
    removed.forces(q1, fr);
    EXPECT_TRUE(same_bits(f, fr)) << cutoff << " " << weight;
  }
}

// ------------------------------------------------------------------------------------------ gradients
// Bonds failed at several nodes (some nodes with two or three frozen slots), then a random configuration
// around it: forces against central differences of the energy (frozen constants included) within 1e-6
// of the largest force, as for the paper's law (RubberForces.MatchFiniteDifferencesInAllBranches: 2e-9
// measured), for both forms of the three-body sum, both weights, the residual, and the compact cut-off.
TEST(RubberFailure, ForcesMatchFiniteDifferencesWithFrozenTerms) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = 8;
  o.ny = 8;
  o.spacing = 1;
  o.notch = 2.5;
  const Lattice L = build_lattice(frac::mesh::make_triangular_lattice(o));
  const Matrix2d F{{1.2, 0.1}, {0, 3.0}};
  double worst = 0;
  for (const auto& [pair, cutoff, angle, weight, kappa] :
       {std::tuple{"marder", "none", "marder", "pair", 0.0},
        std::tuple{"marder", "fermi", "marder-pairwise", "pair", 0.0},
        std::tuple{"marder-c1", "fermi", "marder", "all_bonds", 0.0},
        std::tuple{"marder", "fermi", "marder", "pair", 0.5},
        std::tuple{"marder-soft", "smoothstep", "marder", "pair", 0.0}}) {
    const double width = std::string(cutoff) == "smoothstep" ? 0.2 : 0.05;
    const BondLaw law = natural_law(1.5, 0.1, 2.75, width, pair, cutoff, angle, weight);
    ModelOptions mo = options(law, Failure::freeze);
    if (kappa > 0) mo.residual = three_body_residual(law, L, F, kappa);
    Model model(L, mo);
    // Fail the bonds that a pull of the sheet's middle row takes past u_c.
    auto q = deformed(model, F);
    frac::Rng rng(31);
    for (double& x : q) x += rng.uniform(-0.1, 0.1);
    const std::size_t n = model.nodes();
    for (std::size_t i = 0; i < n; ++i)
      if (L.ry[i] > 3.4) q[n + i] += 0.25;
    std::vector<double> v(q.size(), 0.0), a(q.size());
    model.accelerations(0, q, v, a);
    const int failed = model.pending_breaks();
    EXPECT_GT(failed, 4) << cutoff;
    // Then pulled back so that no intact bond sits at a kink of f (Δ + u_s, u_c) within 2e-4.
    for (std::size_t i = 0; i < n; ++i)
      if (L.ry[i] > 3.4) q[n + i] -= 0.25;
    std::vector<double> qk;
    for (;;) {
      qk = q;
      for (double& x : qk) x += rng.uniform(-0.02, 0.02);
      bool ok = true;
      for (std::size_t b = 0; b < L.bonds(); ++b) {
        if (model.status(b) != kIntact) continue;
        const double u = model.bond_length(b, qk);
        ok = ok && std::abs(u - 1.1) > 2e-4 && std::abs(u - 2.75) > 2e-4;
      }
      if (ok) break;
    }
    // The compact cut-off has h(u_c) = 0: a bond failing there has no three-body term left to freeze.
    if (std::string(cutoff) == "smoothstep")
      EXPECT_EQ(model.potential_energy(qk).frozen, 0.0);
    else
      EXPECT_NE(model.potential_energy(qk).frozen, 0.0) << cutoff;
    const double err = fd_error(model, qk);
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-6) << pair << " " << cutoff << " " << angle << " " << weight << " κ " << kappa;
  }
  std::cout << "[measured] freeze, forces vs central differences with frozen terms: worst error / max |F| = " << worst
            << "\n";
}

// ------------------------------------------------------------------------------------------ far field
// Until a bond fails the energy-neutral law is the paper's, bit for bit: the homogeneous energy and
// virial (the continuum limit) and a standing wave on a periodic patch at (1.2, 3) (the wave speeds) give
// the same numbers with either law, so RubberContinuum.* and RubberWaves.* hold with the option on.
TEST(RubberFailure, FarFieldIsThePapersBitForBit) {
  const Matrix2d F{{1.2, 0}, {0, 3.0}};
  const double u0 = std::hypot(0.6, 1.5 * std::sqrt(3.0));
  for (const char* cutoff : {"none", "fermi"}) {
    const BondLaw law = natural_law(1.5, 0.1, u0 + 0.75, 0.05, "marder", cutoff);  // u_c = u_0 + 15 widths
    std::vector<double> q_end[2], e_end[2];
    for (const Failure failure : {Failure::paper, Failure::freeze}) {
      Model model(periodic_lattice(32, 4), options(law, failure));
      model.set_box(F);
      auto q = deformed(model, F);
      const std::size_t n = model.nodes();
      for (std::size_t i = 0; i < n; ++i) q[i] += 0.01 * std::cos(2 * std::numbers::pi * model.lattice().rx[i] / 32);
      frac::dynamics::VelocityVerlet verlet;
      verlet.start(model, 0, 0.01, q, std::vector<double>(q.size(), 0.0));
      for (int s = 0; s < 2000; ++s) verlet.step(model);
      EXPECT_EQ(model.pending_breaks(), 0);
      const auto k = static_cast<std::size_t>(failure == Failure::freeze);
      q_end[k].assign(verlet.q().begin(), verlet.q().end());
      const auto qh = deformed(model, F);
      const Matrix2d w = model.virial(qh);
      e_end[k] = {model.potential_energy(qh).total(), w(0, 0), w(0, 1), w(1, 1)};
    }
    EXPECT_TRUE(same_bits(q_end[0], q_end[1])) << cutoff;
    EXPECT_TRUE(same_bits(e_end[0], e_end[1])) << cutoff;
  }
}

// ------------------------------------------------------------------------------------------ energy
// A strip as rubber-run builds it (scene → prepare_rubber → build_rubber), Δ = 1 mm, √a = 40 m/s.
struct Strip {
  RubberSetup setup;
  RubberSystem sys;
};
Strip make_strip(std::int64_t nx, std::int64_t ny, const std::string& keys, int threads = 1) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = 1e-3;
  const auto m = frac::mesh::make_triangular_lattice(o);
  frac::Scene scene = frac::Scene::parse(keys, "failure.ini");
  const RubberScene sc = read_rubber_scene(scene, m);
  scene.check_all_used();
  Strip s{prepare_rubber(sc, m), {}};
  s.sys = build_rubber(m, s.setup, 5, threads);
  return s;
}

std::string with_dt(const std::string& keys, double dt) {
  std::ostringstream s;
  s.precision(17);
  s << keys << "[integrator]\ndt = " << dt << "\n";
  return s.str();
}

struct EnergyRun {
  double worst = 0;   // max |E(t) − E(0)| over the run, J
  double frozen = 0;  // J
  std::size_t breaks = 0;
  std::vector<double> q;  // at the end
};

// 40 × 16 strip at (1.2, 3), b = 1.5, a 10Δ seed kicked open: the path cut-off 0.13Δ above the far field
// and the bulk's 1.3 times it; 10 time units, the energy sampled every step.
EnergyRun run_strip(const std::string& law_keys, double dt) {
  const std::string keys = "[loading]\nstretch_x = 1.2\nstretch_y = 3\n[law]\ncutoff = none\ncutoff_length = 2.8e-3\n" +
                           law_keys + "[crack]\nseed_length = 0.01\ntip_kick = 20\npath_cutoff_ratio = 1.3\n";
  Strip s = make_strip(40, 16, with_dt(keys, dt));
  Model& model = *s.sys.model;
  frac::dynamics::VelocityVerlet verlet;
  verlet.start(model, 0, dt, s.sys.q0, s.sys.v0);
  auto energy = [&] { return model.kinetic_energy(verlet.v()) + model.potential_energy(verlet.q()).total(); };
  const double e0 = energy();
  EnergyRun r;
  const auto steps = static_cast<long>(std::llround(2.5e-4 / dt));
  for (long k = 1; k <= steps; ++k) {
    verlet.step(model);
    r.breaks += static_cast<std::size_t>(model.pending_breaks());
    model.clear_breaks();
    r.worst = std::max(r.worst, std::abs(energy() - e0));
  }
  r.frozen = model.potential_energy(verlet.q()).frozen;
  r.q.assign(verlet.q().begin(), verlet.q().end());
  return r;
}

// Hundreds of bonds fail (the strip tears along the path and the bulk behind the tip frays). With the
// energy-neutral law the total energy stays within 1 % of the three-body energy frozen (the failures'
// whole bookkeeping; measured 0.05 % at dt = 4e-7 s) and its error shrinks with the step (a failure
// between two steps costs O(dt) of either sign: measured ratio 3.2 from 4e-7 to 1e-7 s; asked ≥ 1.5).
// The paper's law broken irreversibly at u_c (physics.irreversible, breaking.extra_widths → 0) with the same
// cut-off (none: h = 1 up to u_c) exerts the same forces, so it runs the same trajectory, but it books
// the share a failed bond's terms held as lost: its energy changes by what freeze froze.
TEST(RubberFailure, EnergyConservedThroughFailures) {
  const double ma = 8.660254037844386e-7 * 1600;  // J: m a (node mass × a)
  const EnergyRun coarse = run_strip("failure = freeze\n", 4e-7), fine = run_strip("failure = freeze\n", 1e-7);
  const EnergyRun paper = run_strip("[physics]\nirreversible = on\n[breaking]\nextra_widths = 1e-9\n", 4e-7);
  std::cout << "[measured] freeze, 40 x 16 strip through " << coarse.breaks << " and " << fine.breaks
            << " failures: max |E - E0| = " << coarse.worst / ma << " m a (dt = 4e-7 s), " << fine.worst / ma
            << " m a (1e-7 s), frozen " << coarse.frozen / ma
            << " m a; the paper's law broken at u_c: " << paper.worst / ma << " m a over " << paper.breaks
            << " failures\n";
  EXPECT_GT(coarse.breaks, 200u);
  EXPECT_LT(coarse.worst, 1e-2 * std::abs(coarse.frozen));
  EXPECT_LT(fine.worst, coarse.worst / 1.5);
  EXPECT_TRUE(same_bits(paper.q, coarse.q));
  EXPECT_GT(paper.worst, 0.9 * std::abs(coarse.frozen));
}

// ------------------------------------------------------------------------------------------ threads
// rubber-run's path with every failure-related switch on (freeze, the crack path, toughening of the
// retracting faces, near-failure Kelvin damping) on 1, 2 and 3 threads: identical positions,
// velocities, accelerations and frozen energy after 300 steps in which bonds fail and faces toughen.
TEST(RubberFailure, BitIdenticalForAnyNumberOfThreads) {
  const std::string keys =
      "[loading]\nstretch_x = 1.2\nstretch_y = 3\n[law]\ncutoff = none\ncutoff_length = 2.8e-3\nfailure = freeze\n"
      "[crack]\nseed_length = 0.01\ntip_kick = 20\npath_cutoff_ratio = 1.2\n[physics]\ntoughening = on\n"
      "damping = on\n[damping]\nkind = near_failure\nonset = 2.7e-3\n[toughening]\ncutoff = 3.6e-3\n"
      "[initial]\nnoise = 2\n";
  std::vector<double> ref_q, ref_v, ref_a;
  double ref_frozen = 0;
  for (int threads : {1, 2, 3}) {
    Strip s = make_strip(40, 24, with_dt(keys, 2e-7), threads);
    Model& model = *s.sys.model;
    frac::dynamics::VelocityVerlet verlet;
    verlet.start(model, 0, 2e-7, s.sys.q0, s.sys.v0);
    std::size_t breaks = 0, toughened = 0;
    for (int k = 1; k <= 300; ++k) {
      verlet.step(model);
      breaks += static_cast<std::size_t>(model.pending_breaks());
      model.clear_breaks();
      if (k % 10 == 0) toughened += model.toughen(verlet.q(), 1.5e-3, 3.6e-3);
    }
    EXPECT_GT(breaks, 10u);
    EXPECT_GT(toughened, 0u);
    const double frozen = model.potential_energy(verlet.q()).frozen;
    if (threads == 1) {
      ref_q.assign(verlet.q().begin(), verlet.q().end());
      ref_v.assign(verlet.v().begin(), verlet.v().end());
      ref_a.assign(verlet.a().begin(), verlet.a().end());
      ref_frozen = frozen;
      continue;
    }
    EXPECT_TRUE(same_bits(ref_q, verlet.q())) << threads << " threads";
    EXPECT_TRUE(same_bits(ref_v, verlet.v())) << threads << " threads";
    EXPECT_TRUE(same_bits(ref_a, verlet.a())) << threads << " threads";
    EXPECT_EQ(0, std::memcmp(&ref_frozen, &frozen, sizeof(double))) << threads << " threads";
  }
}

// With a cut-off function, a bond fails at u_c where h(u_c) < 1 (1/2 for Fermi): the share released on the
// way is not frozen, and rubber-run says so with the number; without one (cutoff = none) it does not.
TEST(RubberFailure, WarnsWhenTheCutoffReleasesPartOfTheShare) {
  auto warns = [](const std::string& cutoff) {
    const Strip s = make_strip(20, 8, "[law]\nfailure = freeze\ncutoff = " + cutoff + "\n");
    for (const auto& w : s.setup.warnings)
      if (w.find("law.failure = freeze") != std::string::npos) return w;
    return std::string();
  };
  EXPECT_NE(warns("fermi").find("h = 0.5, so 50%"), std::string::npos) << warns("fermi");
  EXPECT_EQ(warns("none"), "");
}

// ------------------------------------------------------------------------------------------ crack path
// crack.path_cutoff_ratio: the bonds crossing the crack line keep u_c, every other bond gets ratio × u_c;
// ratio 1 (the default) sets nothing (the same bits as a scene without the key); below 1 it is refused.
TEST(RubberCrackPath, CutoffsOnAndOffTheLine) {
  const std::string keys = "[loading]\nstretch_x = 1.2\nstretch_y = 3\n[law]\ncutoff_length = 3e-3\n";
  Strip weak = make_strip(30, 12, keys + "[crack]\npath_cutoff_ratio = 1.25\n");
  const Model& m = *weak.sys.model;
  const CrackPath& path = *weak.sys.path;
  std::vector<std::uint8_t> on_path(m.lattice().bonds(), 0);
  for (std::size_t k = 0; k < path.size(); ++k) on_path[path.bond(k)] = 1;
  std::size_t line = 0, bulk = 0;
  for (std::size_t b = 0; b < m.lattice().bonds(); ++b) {
    if (!m.lattice().exists[b]) continue;
    if (on_path[b]) {
      EXPECT_EQ(m.cutoff(b), 3e-3);
      ++line;
    } else {
      EXPECT_DOUBLE_EQ(m.cutoff(b), 1.25 * 3e-3);
      ++bulk;
    }
  }
  EXPECT_EQ(line, 2u * 30 - 1);  // the two diagonal families between the middle rows
  EXPECT_GT(bulk, 10 * line);
  // Ratio 1: every cut-off is u_c, and a short run is the run without the key, bit for bit.
  Strip one = make_strip(30, 12, keys + "[crack]\npath_cutoff_ratio = 1\nseed_length = 0.008\ntip_kick = 40\n");
  Strip none = make_strip(30, 12, keys + "[crack]\nseed_length = 0.008\ntip_kick = 40\n");
  for (std::size_t b = 0; b < one.sys.model->lattice().bonds(); ++b) EXPECT_EQ(one.sys.model->cutoff(b), 3e-3);
  std::unique_ptr<frac::dynamics::Integrator> in[2];
  Strip* s[2] = {&one, &none};
  for (int k = 0; k < 2; ++k) {
    in[k] = frac::dynamics::make_integrator(frac::dynamics::IntegratorKind::verlet);
    in[k]->start(*s[k]->sys.model, 0, s[k]->setup.dt, s[k]->sys.q0, s[k]->sys.v0);
    for (int step = 0; step < 200; ++step) in[k]->step(*s[k]->sys.model);
  }
  EXPECT_TRUE(same_bits(in[0]->q(), in[1]->q()));
  EXPECT_THROW(make_strip(30, 12, keys + "[crack]\npath_cutoff_ratio = 0.9\n"), frac::UsageError);
}

}  // namespace
