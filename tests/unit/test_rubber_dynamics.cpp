// Rubber lattice under the shared integrators (dynamics/integrator.hpp): momentum conservation, the
// dt² scaling of the velocity-Verlet energy error, no secular drift over 10^4 steps
// (physics/rubber-lattice.md §5), clamps, and bond failure (events, irreversible breaking, damping).
// Units: m = Δ = a = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>

#include "continuum/mooney_rivlin.hpp"
#include "core/rng.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/lattice.hpp"
#include "rubber/model.hpp"
#include "rubber_test_support.hpp"

namespace {

namespace mr = frac::mr;

using namespace frac::rubber;
using Eigen::Matrix2d;
using Eigen::Vector2d;

using test::deformed;
using test::natural_law;

std::unique_ptr<Model> make_model(const BondLaw& law, std::int64_t nx, std::int64_t ny, bool periodic,
                                  DampingKind damping = DampingKind::none, double beta = 0, int threads = 1) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = 1;
  ModelOptions mo;
  mo.law = law;
  mo.damping = damping;
  mo.beta = beta;
  mo.threads = threads;
  return std::make_unique<Model>(build_lattice(frac::mesh::make_triangular_lattice(o), periodic, periodic), mo);
}

// Random velocities of amplitude v0 with zero total momentum.
std::vector<double> thermal(std::size_t n, double v0, std::uint64_t seed) {
  frac::Rng rng(seed);
  std::vector<double> v(2 * n);
  for (double& x : v) x = rng.uniform(-v0, v0);
  for (int c = 0; c < 2; ++c) {
    double mean = 0;
    for (std::size_t i = 0; i < n; ++i) mean += v[c * n + i];
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) v[c * n + i] -= mean;
  }
  return v;
}

double total_energy(Model& model, const frac::dynamics::Integrator& integ) {
  return model.potential_energy(integ.q()).total() + model.kinetic_energy(integ.v());
}

// ------------------------------------------------------------------------------------------ momentum
TEST(RubberDynamics, MomentumConservedOnAFreeSheet) {
  for (const DampingKind damping : {DampingKind::none, DampingKind::uniform}) {
    const BondLaw law = natural_law(1.5, 0.1, 2.0, 0.05);
    auto model = make_model(law, 12, 10, false, damping, 0.3);
    auto q = deformed(*model, Matrix2d{{1.3, 0.05}, {0, 1.25}});
    frac::Rng rng(2);
    for (double& x : q) x += rng.uniform(-0.03, 0.03);
    std::vector<double> v(q.size());
    for (double& x : v) x = rng.uniform(-0.05, 0.1);  // net momentum on purpose
    const std::size_t n = model->nodes();
    auto momentum = [n](std::span<const double> vel) {
      Vector2d p(0, 0);
      for (std::size_t i = 0; i < n; ++i) p += Vector2d(vel[i], vel[n + i]);
      return p;
    };
    double scale = 0;
    for (double x : v) scale += std::abs(x);
    frac::dynamics::VelocityVerlet verlet;
    verlet.start(*model, 0, 0.01, q, v);
    const Vector2d p0 = momentum(verlet.v());
    double worst = 0;
    for (int s = 0; s < 2000; ++s) {
      verlet.step(*model);
      worst = std::max(worst, (momentum(verlet.v()) - p0).norm() / scale);
    }
    EXPECT_LT(worst, 1e-10);
    std::cout << "[measured] momentum drift / sum |m v| over 2000 steps"
              << (damping == DampingKind::none ? "" : " (Kelvin damping on)") << ": " << worst << "\n";
  }
}

// ------------------------------------------------------------------------------------------ energy
struct EnergyTrace {
  double max_fluctuation = 0;  // max |E − E0| / KE0
  double drift = 0;            // |mean of the last tenth − mean of the first tenth| / KE0
  double ke0 = 0;
};

// Periodic 12 × 12 lattice at λ = (1.5, 3), b = 1.5, thermal noise (§5 of the note).
EnergyTrace run_thermal(double dt, double t_end, int threads = 1) {
  const BondLaw law = natural_law(1.5, 0.1, 4.5, 0.1);
  auto model = make_model(law, 12, 12, true, DampingKind::none, 0, threads);
  const Matrix2d F{{1.5, 0}, {0, 3.0}};
  model->set_box(F);
  const auto q = deformed(*model, F);
  const auto v = thermal(model->nodes(), 0.02, 17);
  frac::dynamics::VelocityVerlet verlet;
  verlet.start(*model, 0, dt, q, v);
  EnergyTrace tr;
  tr.ke0 = model->kinetic_energy(verlet.v());
  const double e0 = total_energy(*model, verlet);
  const auto steps = static_cast<long>(std::llround(t_end / dt));
  const long window = steps / 10;
  double first = 0, last = 0;
  for (long s = 1; s <= steps; ++s) {
    verlet.step(*model);
    const double e = total_energy(*model, verlet);
    tr.max_fluctuation = std::max(tr.max_fluctuation, std::abs(e - e0) / tr.ke0);
    if (s <= window) first += e;
    if (s > steps - window) last += e;
  }
  tr.drift = std::abs(last - first) / static_cast<double>(window) / tr.ke0;
  return tr;
}

TEST(RubberDynamics, VerletEnergyErrorScalesAsDtSquared) {
  const EnergyTrace a = run_thermal(0.01, 20), b = run_thermal(0.02, 20);
  const double ratio = b.max_fluctuation / a.max_fluctuation;
  std::cout << "[measured] |dE|/KE0 over 20 time units: " << a.max_fluctuation << " at dt = 0.01, " << b.max_fluctuation
            << " at dt = 0.02 (ratio " << ratio << ", dt^2 gives 4)\n";
  EXPECT_GT(ratio, 3.2);
  EXPECT_LT(ratio, 4.8);
  EXPECT_LT(a.max_fluctuation, 1e-2);
}

TEST(RubberDynamics, NoSecularDriftOverTenThousandVerletSteps) {
  const EnergyTrace tr = run_thermal(0.01, 100);  // 10^4 steps
  std::cout << "[measured] energy drift over 10^4 Verlet steps (dt = 0.01): " << tr.drift
            << " of the initial kinetic energy (fluctuation " << tr.max_fluctuation << ")\n";
  EXPECT_LT(tr.drift, 1e-4);
}

TEST(RubberDynamics, ThreadCountDoesNotChangeATrajectory) {
  // Same run on 1 and 2 threads: identical energies (hence identical states) bit for bit.
  const BondLaw law = natural_law(1.5, 0.1, 4.5, 0.1);
  std::vector<double> finals[2];
  for (int t = 0; t < 2; ++t) {
    auto model = make_model(law, 30, 20, false, DampingKind::uniform, 0.2, t + 1);
    const auto q = deformed(*model, Matrix2d{{1.2, 0}, {0, 1.5}});
    const auto v = thermal(model->nodes(), 0.05, 4);
    frac::dynamics::VelocityVerlet verlet;
    verlet.start(*model, 0, 0.01, q, v);
    for (int s = 0; s < 200; ++s) verlet.step(*model);
    finals[t].assign(verlet.q().begin(), verlet.q().end());
  }
  EXPECT_EQ(0, std::memcmp(finals[0].data(), finals[1].data(), finals[0].size() * sizeof(double)));
}

// ------------------------------------------------------------------------------------------ clamps, failure
TEST(RubberDynamics, ClampedNodesStayPut) {
  const BondLaw law = natural_law(1.5, 0.1, 4.5, 0.1);
  auto model = make_model(law, 10, 8, false);
  auto q = deformed(*model, Matrix2d{{1.2, 0}, {0, 2.0}});
  const std::vector<std::size_t> fixed = {0, 1, 2, 77, 78, 79};
  model->clamp(fixed, q);
  const auto v = thermal(model->nodes(), 0.05, 8);
  for (const auto kind : {frac::dynamics::IntegratorKind::verlet, frac::dynamics::IntegratorKind::gear5}) {
    auto integ = frac::dynamics::make_integrator(kind);
    integ->start(*model, 0, 0.01, q, v);
    for (int s = 0; s < 300; ++s) integ->step(*model);
    const std::size_t n = model->nodes();
    for (std::size_t i : fixed) {
      EXPECT_EQ(integ->q()[i], q[i]);
      EXPECT_EQ(integ->q()[n + i], q[n + i]);
      EXPECT_EQ(integ->v()[i], 0.0);
    }
    // The free nodes moved (the strip contracts along x: the material is not stress-free at 1.2 x 2).
    EXPECT_NE(integ->q()[40], q[40]);
  }
}

TEST(RubberDynamics, BondsPastTheCutoffAreEventsAndBreakIrreversiblyWhenAsked) {
  LawParams p;
  p.spacing = 1;
  p.A = 1;
  p.B = mr::lattice_B(1, 1, 1.5, 1);
  p.short_width = 0.1;
  p.cutoff = 1.5;
  p.cutoff_width = 0.02;
  frac::mesh::TriangularLatticeOptions o{6, 6, 1.0, "x", 0.0};
  const Lattice L = build_lattice(frac::mesh::make_triangular_lattice(o));
  for (const bool irreversible : {false, true}) {
    ModelOptions mo;
    mo.law = make_bond_law(p);
    mo.break_extra = irreversible ? 10 * p.cutoff_width : std::numeric_limits<double>::infinity();
    Model model(L, mo);
    // Pull node 14 up by 2Δ: its two horizontal bonds and its two bonds downwards pass u_c + 10 widths.
    auto q = deformed(model, Matrix2d::Identity());
    const double e_ref = model.potential_energy(q).total();  // not zero: the free edges
    const std::size_t n = model.nodes();
    q[n + 14] += 2.0;
    std::vector<double> v(q.size()), a(q.size());
    model.accelerations(0, q, v, a);
    EXPECT_GT(model.pending_events(), 0);
    std::vector<std::size_t> events;
    model.take_events(events);
    EXPECT_EQ(static_cast<int>(events.size()), 4);
    EXPECT_EQ(model.pending_events(), 0);
    model.accelerations(0, q, v, a);
    events.clear();
    model.take_events(events);
    EXPECT_TRUE(events.empty());  // recorded once
    EXPECT_EQ(model.pending_breaks(), irreversible ? 4 : 0);
    // Pushed back, a broken bond stays broken; a reversible one pulls again.
    q[n + 14] -= 2.0;
    const double e = model.potential_energy(q).total();
    if (irreversible) {
      // Four broken bonds keep 2 f(u_c) each and lose their three-body terms.
      EXPECT_GT(std::abs(e - e_ref), 1.0);
    } else {
      EXPECT_NEAR(e, e_ref, 1e-9 * std::abs(e_ref));
    }
  }
}

}  // namespace
