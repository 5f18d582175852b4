// Rubber-lattice physics that a scene leaves out costs nothing and changes nothing (issue 7 §3), shown for
// the Kelvin damping along bonds (physics.damping):
//   - off, the damping code never runs: with damping off the model is handed a NaN β (and NaN onset) and
//     NaN velocities, and its forces stay finite and equal, bit for bit, to those of a model with β = 0
//     and real velocities (had the damping term run, every force would be NaN: checked with damping on);
//   - on with β = 0, a run is the same as with damping off, bit for bit, step by step (both damping kinds,
//     both integrators), through rubber-run's own set-up; a nonzero β does change it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/rng.hpp"
#include "core/scene.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/lattice.hpp"
#include "rubber/model.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"
#include "rubber_test_support.hpp"

namespace {

using namespace frac::rubber;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A 12 × 10 sheet (free edges, or periodic) stretched to (1.3, 1.25) with random displacements: bonds of
// every length up to the cut-off region (u_c = 2, width 0.05).
struct Sheet {
  Lattice lattice;
  std::vector<double> q;
};
Sheet make_sheet(bool periodic) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = 12;
  o.ny = 10;
  o.spacing = 1;
  Sheet s{build_lattice(frac::mesh::make_triangular_lattice(o), periodic, periodic), {}};
  const std::size_t n = s.lattice.n;
  s.q.resize(2 * n);
  frac::Rng rng(3);
  for (std::size_t i = 0; i < n; ++i) {
    s.q[i] = 1.3 * s.lattice.rx[i] + rng.uniform(-0.05, 0.05);
    s.q[n + i] = 1.25 * s.lattice.ry[i] + rng.uniform(-0.05, 0.05);
  }
  return s;
}

std::vector<double> accelerations(const Sheet& s, DampingKind kind, double beta, double onset,
                                  std::span<const double> v) {
  ModelOptions mo;
  mo.law = frac::rubber::test::natural_law(1.5, 0.1, 2.0, 0.05);
  mo.damping = kind;
  mo.beta = beta;
  mo.damping_onset = onset;
  Model model(s.lattice, mo);
  model.set_box(Eigen::Matrix2d{{1.3, 0}, {0, 1.25}});
  std::vector<double> a(s.q.size());
  model.accelerations(0, s.q, v, a);
  return a;
}

TEST(RubberSwitches, DampingOffNeverRunsTheDampingCode) {
  for (const bool periodic : {false, true}) {
    const Sheet s = make_sheet(periodic);
    std::vector<double> v(s.q.size()), poisoned(s.q.size(), kNaN);
    frac::Rng rng(5);
    for (double& x : v) x = rng.uniform(-0.1, 0.1);
    const auto reference = accelerations(s, DampingKind::none, 0, 0, v);
    const auto off = accelerations(s, DampingKind::none, kNaN, kNaN, poisoned);
    for (double x : reference) ASSERT_TRUE(std::isfinite(x));
    EXPECT_TRUE(same_bits(reference, off)) << (periodic ? "periodic" : "free edges");
    // The poison would show: with damping on, a NaN β (or NaN velocities) makes every force NaN.
    for (const DampingKind kind : {DampingKind::uniform, DampingKind::near_failure}) {
      const auto on = accelerations(s, kind, kNaN, 1.0, v);
      EXPECT_TRUE(std::isnan(on[0]) && std::isnan(on[on.size() / 2]));
      const auto on_v = accelerations(s, kind, 0.3, 1.0, poisoned);
      EXPECT_TRUE(std::isnan(on_v[0]) && std::isnan(on_v[on.size() / 2]));
    }
  }
}

// rubber-run's path: the stretch scene (1.2, 3) on a 40 × 16 strip with a seed crack kicked open at √a,
// thermal noise and u_c = 2.85Δ, 3.7 widths above the far field, so that bonds fail within the 4 time
// units compared (about 20); damping off against damping on with β = 0, stepped side by side.
struct Twin {
  RubberSetup setup;
  RubberSystem sys;
  std::unique_ptr<frac::dynamics::Integrator> in;
};
Twin make_run(const frac::mesh::NodeMesh& m, const std::string& extra) {
  const std::string text =
      "[loading]\nstretch_x = 1.2\nstretch_y = 3\n[law]\ncutoff_length = 2.85e-3\n[boundary]\nclamp_columns = 2\n"
      "[crack]\nseed_length = 0.01\ntip_kick = 40\n[initial]\nnoise = 2\n" +
      extra;
  frac::Scene scene = frac::Scene::parse(text, "switches.ini");
  const RubberScene sc = read_rubber_scene(scene, m);
  scene.check_all_used();
  Twin r{prepare_rubber(sc, m), {}, nullptr};
  r.sys = build_rubber(m, r.setup, 11, 1);
  r.in = frac::dynamics::make_integrator(sc.integrator);
  r.in->start(*r.sys.model, 0, r.setup.dt, r.sys.q0, r.sys.v0);
  return r;
}

// The first step (1..steps) at which the two runs differ in any bit of positions, velocities or
// accelerations, or −1; and how many bonds went past u_c in the first run.
std::pair<long, std::size_t> first_difference(Twin& a, Twin& b, long steps) {
  std::vector<std::size_t> events;
  for (long s = 1; s <= steps; ++s) {
    a.in->step(*a.sys.model);
    b.in->step(*b.sys.model);
    a.sys.model->take_events(events);
    if (!same_bits(a.in->q(), b.in->q()) || !same_bits(a.in->v(), b.in->v()) || !same_bits(a.in->a(), b.in->a()))
      return {s, events.size()};
  }
  return {-1, events.size()};
}

TEST(RubberSwitches, DampingOnWithZeroBetaEqualsDampingOff) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = 40;
  o.ny = 16;
  o.spacing = 1e-3;
  const auto m = frac::mesh::make_triangular_lattice(o);
  for (const char* integrator : {"verlet", "gear5"}) {
    const std::string kind = std::string("[integrator]\nkind = ") + integrator + "\n";
    Twin off = make_run(m, kind);
    EXPECT_EQ(off.sys.model->options().damping, DampingKind::none);
    for (const char* damping : {"uniform", "near_failure"}) {
      Twin base = make_run(m, kind);
      Twin zero = make_run(m, kind + "[physics]\ndamping = on\n[damping]\nbeta = 0\nkind = " + damping + "\n");
      EXPECT_NE(zero.sys.model->options().damping, DampingKind::none);
      EXPECT_EQ(base.setup.dt, zero.setup.dt);
      const auto steps = static_cast<long>(std::ceil(4 * 25e-6 / base.setup.dt));  // 4 time units Δ/√a
      const auto [diff, events] = first_difference(base, zero, steps);
      EXPECT_EQ(diff, -1) << integrator << ", " << damping << ": runs differ from step " << diff;
      EXPECT_GT(events, 0u) << integrator << ": the comparison should see bonds fail";
      // A nonzero β does change the run (the comparison can see damping at all).
      Twin base2 = make_run(m, kind);
      Twin some = make_run(m, kind + "[physics]\ndamping = on\n[damping]\nkind = " + damping + "\n");
      EXPECT_NE(first_difference(base2, some, steps).first, -1) << integrator << ", " << damping;
    }
  }
}

}  // namespace
