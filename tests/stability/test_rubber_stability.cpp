// Hard cases of the rubber lattice (issue 7 §2): stretches up to λ = 5, bonds held at the cut-off, a
// node whose six bonds are all broken, a node flying off the lattice, and 10^6 steps of a small elastic
// lattice per integrator. Each case is built the way rubber-run builds it (scene → prepare_rubber →
// build_rubber: the same law, node mass and automatic time step) and then stepped here, so that every
// step can be checked: no NaN or infinity, total energy (kinetic + potential) bounded by its input, and
// momentum conserved (every case is a periodic sheet with nothing clamped). A state the set-up warns
// about is asserted to be warned about, naming its numbers.
//
// Units: SI as in the scenes (Δ = 1 mm, √a = 40 m/s, time unit τ = Δ/√a = 25 µs); the printed numbers
// are relative. Tolerances are stated at each case with the measured value they cover.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/scene.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/model.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"

namespace frac::rubber {
namespace {

constexpr double kSpacing = 1e-3;           // m, Δ
constexpr double kSqrtA = 40;               // m/s, √a of the scenes (material.a = 1600)
constexpr double kTau = kSpacing / kSqrtA;  // s, the natural time unit

mesh::NodeMesh sheet(std::int64_t nx, std::int64_t ny) {
  mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = kSpacing;
  return mesh::make_triangular_lattice(o);
}

// A periodic sheet (nothing clamped) held at (λx, λy), thermal noise of `noise` √a, plus `extra` scene
// lines; the set-up and the initial state of rubber-run.
struct Rig {
  RubberSetup setup;
  RubberSystem sys;
};
Rig make_rig(const mesh::NodeMesh& m, double lx, double ly, double noise, const std::string& extra = "") {
  std::ostringstream text;
  text.precision(17);
  text << "[loading]\nkind = stretch\nstretch_x = " << lx << "\nstretch_y = " << ly
       << "\n[boundary]\nclamp_rows = 0\nclamp_columns = 0\nperiodic = xy\n[initial]\nnoise = " << noise * kSqrtA
       << "\n"
       << extra;
  Scene s = Scene::parse(text.str(), "stability.ini");
  const RubberScene sc = read_rubber_scene(s, m);
  s.check_all_used();
  Rig r{prepare_rubber(sc, m), {}};
  r.sys = build_rubber(m, r.setup, 7, 1);
  return r;
}

// Σ v (the nodes have equal masses) and Σ |v|, the scale it is compared with.
struct Momentum {
  double px = 0, py = 0, scale = 0;
};
Momentum momentum(std::span<const double> v) {
  const std::size_t n = v.size() / 2;
  Momentum p;
  for (std::size_t i = 0; i < n; ++i) {
    p.px += v[i];
    p.py += v[n + i];
    p.scale += std::hypot(v[i], v[n + i]);
  }
  return p;
}

bool all_finite(std::span<const double> x) {
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return true;
}

// What a run did: the largest deviation of the total energy from its start, the kinetic energy at the
// start and the largest reached, the momentum drift, and whether everything stayed finite.
struct Trace {
  double e0 = 0, ke0 = 0, ke_max = 0, pe0 = 0;
  double max_dev = 0;   // max |E − E0|, J
  double max_rise = 0;  // max (E − E0), J: heating
  double drift = 0;     // |mean of the last tenth − mean of the first tenth| of E, J
  double momentum = 0;  // max |Σv − Σv(0)| / max Σ|v| (the largest momentum scale of the run)
  bool finite = true;
  long long steps = 0;
};

// Steps `in` (already started) `steps` times, checking every step for non-finite forces and every
// `every` steps the energy and momentum; `each` is called after every step.
template <class Each>
Trace integrate(Model& model, dynamics::Integrator& in, long long steps, long long every, Each&& each) {
  Trace tr;
  tr.ke0 = model.kinetic_energy(in.v());
  tr.pe0 = model.potential_energy(in.q()).total();
  tr.e0 = tr.ke0 + tr.pe0;
  tr.ke_max = tr.ke0;
  const Momentum p0 = momentum(in.v());
  double dp = 0, p_scale = p0.scale;
  const long long samples = steps / every, window = std::max(samples / 10, 1LL);
  double first = 0, last = 0;
  long long sample = 0;
  for (long long s = 1; s <= steps; ++s) {
    in.step(model);
    tr.steps = s;
    if (model.nonfinite() > 0) {
      tr.finite = false;
      ADD_FAILURE() << "non-finite force at step " << s << ": " << model.diagnose_nonfinite(in.q(), in.a());
      return tr;
    }
    each(s);
    if (s % every != 0 && s != steps) continue;
    if (!all_finite(in.q()) || !all_finite(in.v())) {
      tr.finite = false;
      ADD_FAILURE() << "non-finite state at step " << s;
      return tr;
    }
    const double ke = model.kinetic_energy(in.v());
    const double e = ke + model.potential_energy(in.q()).total();
    tr.ke_max = std::max(tr.ke_max, ke);
    tr.max_dev = std::max(tr.max_dev, std::abs(e - tr.e0));
    tr.max_rise = std::max(tr.max_rise, e - tr.e0);
    const Momentum p = momentum(in.v());
    dp = std::max(dp, std::hypot(p.px - p0.px, p.py - p0.py));
    p_scale = std::max(p_scale, p.scale);
    tr.momentum = dp / p_scale;
    if (s % every == 0) {
      ++sample;
      if (sample <= window) first += e;
      if (sample > samples - window) last += e;
    }
  }
  tr.drift = std::abs(last - first) / static_cast<double>(window);
  return tr;
}
Trace integrate(Model& model, dynamics::Integrator& in, long long steps, long long every) {
  return integrate(model, in, steps, every, [](long long) {});
}

std::unique_ptr<dynamics::Integrator> start(Rig& r, dynamics::IntegratorKind kind) {
  auto in = dynamics::make_integrator(kind);
  in->start(*r.sys.model, 0, r.setup.dt, r.sys.q0, r.sys.v0);
  return in;
}

// "4.371Δ" as the set-up's messages write a length in spacings.
std::string spacings(double u) {
  std::ostringstream s;
  s.precision(4);
  s << u / kSpacing << "Δ)";
  return s.str();
}

// ------------------------------------------------------------------------------------------ λ up to 5
// With the note's default cut-off u_c = 3.5Δ a stretch of 5 puts far-field bonds past u_c: the set-up
// does not refuse it (a sheet without cohesion is a legitimate, if odd, scene) but warns, naming the
// bond length, the cut-off and what it means. The same sheet still runs: its bonds carry no force past
// u_c (f is constant there and h ≈ 0), so the nodes keep their thermal velocities.
TEST(RubberStability, StretchOfFiveBeyondTheDefaultCutoffIsWarnedAboutNamingTheNumbers) {
  const auto m = sheet(12, 12);
  for (const auto& [lx, ly] : {std::pair{5.0, 5.0}, std::pair{1.2, 5.0}}) {
    Rig r = make_rig(m, lx, ly, 0.02);
    double u0 = 0;
    for (double u : r.setup.family_length) u0 = std::max(u0, u);
    bool named = false;
    for (const auto& w : r.setup.warnings) {
      named = named || (w.find("are past the cut-off u_c = 0.0035 m (3.5Δ)") != std::string::npos &&
                        w.find("no cohesion") != std::string::npos && w.find(spacings(u0)) != std::string::npos);
    }
    EXPECT_TRUE(named) << "(" << lx << ", " << ly << "): no warning naming u_0 = " << spacings(u0)
                       << " past u_c = 3.5Δ; warnings: " << (r.setup.warnings.empty() ? "none" : r.setup.warnings[0]);
    auto in = start(r, dynamics::IntegratorKind::verlet);
    const Trace tr = integrate(*r.sys.model, *in, 2000, 10);
    EXPECT_TRUE(tr.finite);
    EXPECT_LE(tr.max_dev, 1e-3 * tr.ke0) << lx << ", " << ly;
    EXPECT_LE(tr.momentum, 1e-10) << lx << ", " << ly;
    std::printf(
        "[measured] (%g, %g), u_c = 3.5Δ (warned): u_0 = %.4gΔ, dt = %.3g τ, 2000 Verlet steps: "
        "|ΔE| %.2e of KE0, momentum %.1e\n",
        lx, ly, u0 / kSpacing, r.setup.dt / kTau, tr.max_dev / tr.ke0, tr.momentum);
  }
}

// The same stretches with a cut-off 20 widths above the longest far-field bond (no warning): the sheet
// holds at λ = 5, its long waves are real (the lattice is stable there), and a thermal run of 5000 steps
// at the automatic step keeps its energy (the stored energy is 10^5 to 10^6 times the thermal KE0; the
// deviation is stated against KE0, 1 %: measured 5.5e-4 with Verlet, 1.0e-5 with gear5) and momentum.
TEST(RubberStability, StretchOfFiveHeldByAHigherCutoff) {
  const auto m = sheet(12, 12);
  for (const auto& [lx, ly] : {std::pair{5.0, 5.0}, std::pair{1.2, 5.0}}) {
    const double u0 = std::max({lx, std::hypot(0.5 * lx, 0.5 * std::sqrt(3.0) * ly)}) * kSpacing;
    for (const auto kind : {dynamics::IntegratorKind::verlet, dynamics::IntegratorKind::gear5}) {
      std::ostringstream extra;
      extra.precision(17);
      extra << "[law]\ncutoff_length = " << u0 + 20 * 0.05 * kSpacing
            << "\n[integrator]\nkind = " << dynamics::name(kind) << "\n";
      Rig r = make_rig(m, lx, ly, 0.02, extra.str());
      EXPECT_TRUE(r.setup.warnings.empty()) << r.setup.warnings[0];
      EXPECT_FALSE(std::isnan(r.setup.lattice_x.transverse) || std::isnan(r.setup.lattice_x.longitudinal) ||
                   std::isnan(r.setup.lattice_y.transverse) || std::isnan(r.setup.lattice_y.longitudinal));
      auto in = start(r, kind);
      const Trace tr = integrate(*r.sys.model, *in, 5000, 10);
      EXPECT_TRUE(tr.finite);
      EXPECT_LE(tr.max_dev, 1e-2 * tr.ke0) << lx << ", " << ly << ", " << dynamics::name(kind);
      EXPECT_LE(tr.momentum, 1e-10);
      std::printf(
          "[measured] (%g, %g), u_c = u_0 + 20 widths = %.3gΔ, %s: dt = %.3g τ, 5000 steps: max |E − E0| "
          "%.2e of KE0 (stored energy %.3g KE0), momentum %.1e\n",
          lx, ly, u0 / kSpacing + 1, std::string(dynamics::name(kind)).c_str(), r.setup.dt / kTau, tr.max_dev / tr.ke0,
          tr.pe0 / tr.ke0, tr.momentum);
    }
  }
}

// ------------------------------------------------------------------------------------------ u ≈ u_c
// Every bond of the sheet held exactly at its cut-off (λ = 2 both ways, u_c = 2Δ: h = 1/2, the middle of
// the Fermi step) with thermal noise. The set-up warns, naming the numbers: 0 widths between u_0 and u_c,
// and long waves that are unstable there. They are: the sheet fails everywhere at once, bonds cross
// u_c back and forth (reversibly, the paper's law) and about 40 % of the stored energy becomes kinetic.
// The energy that moves is that kinetic energy, KE_max, and the tolerance over 50 τ is stated against it:
//   gear5 at rubber-run's automatic step (safety 0.5): 1 % (measured 0.25 %);
//   Verlet at safety 0.125 (ω_max·dt = 0.25): 1 % (measured 0.28 %);
//   Verlet at the automatic step (safety 0.5, ω_max·dt = 1): stable and bounded, but it heats: +14 % of
//   KE_max in 50 τ (6 % of the stored energy), still growing (+29 % in 120 τ; at dt/2 1.2 %, at dt/4
//   0.28 %). A 25-fold fall for a halved step says the step sits near an edge: the failing sheet is
//   stiffer than the homogeneous states the set-up probes for ω_max. Asserted here: finite and below
//   50 % of KE_max. rubber-run warns at the end of such a run (the energy changed by 8.4 % in 100 τ).
TEST(RubberStability, BondsHeldAtTheCutoff) {
  const auto m = sheet(12, 12);
  struct Case {
    dynamics::IntegratorKind kind;
    double safety, tolerance;
  };
  for (const Case c :
       {Case{dynamics::IntegratorKind::gear5, 0.5, 0.01}, Case{dynamics::IntegratorKind::verlet, 0.125, 0.01},
        Case{dynamics::IntegratorKind::verlet, 0.5, 0.5}}) {
    const std::string name = std::string(dynamics::name(c.kind));
    Rig r = make_rig(
        m, 2, 2, 0.02,
        "[law]\ncutoff_length = 2e-3\n[integrator]\nkind = " + name + "\nsafety = " + std::to_string(c.safety) + "\n");
    bool named = false;
    for (const auto& w : r.setup.warnings)
      named = named ||
              (w.find("is 0 cut-off widths") != std::string::npos && w.find("c_T = unstable") != std::string::npos);
    EXPECT_TRUE(named) << (r.setup.warnings.empty() ? "no warning" : r.setup.warnings[0]);
    long long crossings = 0;
    std::vector<std::size_t> events;
    auto in = start(r, c.kind);
    Model& model = *r.sys.model;
    const auto steps = static_cast<long long>(std::ceil(50 * kTau / r.setup.dt));  // 50 τ, the failure and after
    const Trace tr = integrate(model, *in, steps, 10, [&](long long) {
      events.clear();
      model.take_events(events);
      crossings += static_cast<long long>(events.size());
    });
    EXPECT_TRUE(tr.finite);
    EXPECT_GT(tr.ke_max, 0.1 * std::abs(tr.pe0)) << "the sheet should fail";
    EXPECT_LE(tr.max_dev, c.tolerance * tr.ke_max) << name << ", safety " << c.safety;
    EXPECT_LE(tr.momentum, 1e-10);
    std::printf(
        "[measured] bonds at u_c (λ = 2, u_c = 2Δ), %s at safety %g: dt = %.3g τ, %lld steps, %lld bonds "
        "past u_c, KE_max %.2f of the stored energy: max |E − E0| %.2e of KE_max, momentum %.1e\n",
        name.c_str(), c.safety, r.setup.dt / kTau, steps, crossings, tr.ke_max / std::abs(tr.pe0),
        tr.max_dev / tr.ke_max, tr.momentum);
  }
}

// ------------------------------------------------------------------------------------------ a lone node
// The six bonds of a node in the stretched sheet (1.2, 3), cut (removed, as a seed crack does) or
// failed irreversibly (pulled 10Δ away for one evaluation with physics.irreversible on, then put back):
// the node feels exactly no force and stays where it is, bit for bit; the hole's rim, whose three-body
// sums are now incomplete, rings; energy and momentum are kept.
TEST(RubberStability, ANodeSurroundedByBrokenBonds) {
  const auto m = sheet(12, 12);
  const std::size_t lone = 6 * 12 + 6;
  for (const bool irreversible : {false, true}) {
    Rig r = make_rig(m, 1.2, 3, 0.0, irreversible ? "[physics]\nirreversible = on\n" : "");
    Model& model = *r.sys.model;
    const Lattice& L = model.lattice();
    const std::size_t n = L.n;
    std::vector<std::size_t> bonds;
    for (std::size_t s = 0; s < 6; ++s) {
      const auto j = static_cast<std::size_t>(L.neighbour(lone, static_cast<int>(s)));
      ASSERT_LT(j, n);
      bonds.push_back(s < 3 ? 3 * lone + s : 3 * j + s - 3);
    }
    if (irreversible) {
      std::vector<double> q(r.sys.q0), v(2 * n, 0.0), a(2 * n);
      q[lone] += 10 * kSpacing;
      model.accelerations(0, q, v, a);
      EXPECT_EQ(model.pending_breaks(), 6);
      std::vector<std::size_t> events;
      model.take_events(events);
      model.clear_breaks();
      for (std::size_t b : bonds) EXPECT_EQ(model.status(b), kBroken);
    } else {
      for (std::size_t b : bonds) model.remove_bond(b);
    }
    auto in = start(r, dynamics::IntegratorKind::verlet);
    const double x0 = r.sys.q0[lone], y0 = r.sys.q0[n + lone];
    bool still = true;
    const Trace tr = integrate(model, *in, 4000, 10, [&](long long) {
      still = still && in->q()[lone] == x0 && in->q()[n + lone] == y0 && in->a()[lone] == 0 && in->a()[n + lone] == 0;
    });
    EXPECT_TRUE(tr.finite);
    EXPECT_TRUE(still) << "the lone node moved or felt a force";
    // The energy that moves is the rim's, released from the potential: the deviation is stated against
    // the largest kinetic energy. Verlet at the automatic step (ω_far·dt = 0.09; the rim nodes, with
    // incomplete three-body sums, ring faster): measured 0.56 %; 2 % leaves room for other holes.
    EXPECT_LE(tr.max_dev, 2e-2 * tr.ke_max) << (irreversible ? "broken" : "removed");
    std::printf(
        "[measured] lone node (%s), 4000 Verlet steps of %.3g τ: KE reached %.3g of |E_pot|, |ΔE| %.2e of "
        "it, momentum %.1e\n",
        irreversible ? "bonds broken" : "bonds removed", r.setup.dt / kTau, tr.ke_max / std::abs(tr.pe0),
        tr.max_dev / tr.ke_max, tr.momentum);
    EXPECT_LE(tr.momentum, 1e-10);
  }
}

// ------------------------------------------------------------------------------------------ flying off
// A node of the sheet at (1.2, 3) (the stretch scene's law: u_c = 3.45Δ) given 50 √a = 2000 m/s, 16
// times c_L along x: it tears its six bonds and leaves with 74 % of its kinetic energy. Once every bond
// is beyond u_c + 40 widths the cut-off is exactly 0 and f is constant: the node moves ballistically
// (constant velocity, bit for bit). Energy: the kick is the input. At the automatic step the node
// crosses the cut-off region (width w = 0.05Δ) in a fraction of a step (v·dt = 0.35Δ = 7 widths): the
// step bounds vibrations, not a ballistic speed, and the snap is not resolved. Measured: 2.0 % of the
// kick at the automatic step (tolerance 3 %), 0.15 % at an eighth of it (tolerance 0.5 %): the error is
// discretisation and falls with the step. Irreversible breaking changes nothing here (measured the same).
TEST(RubberStability, AFreeNodeFlyingOff) {
  const auto m = sheet(12, 12);
  const std::size_t node = 6 * 12 + 6;
  const double speed = 50 * kSqrtA;  // m/s
  const double dt_auto = make_rig(m, 1.2, 3, 0.0, "[law]\ncutoff_length = 3.45e-3\n").setup.dt;
  struct Case {
    bool irreversible;
    double step, tolerance;  // step: fraction of the automatic step
  };
  for (const Case c : {Case{false, 1, 0.03}, Case{true, 1, 0.03}, Case{false, 0.125, 0.005}}) {
    std::ostringstream extra;
    extra.precision(17);
    extra << "[law]\ncutoff_length = 3.45e-3\n[integrator]\ndt = " << c.step * dt_auto << "\n";
    if (c.irreversible) extra << "[physics]\nirreversible = on\n";
    Rig r = make_rig(m, 1.2, 3, 0.0, extra.str());
    Model& model = *r.sys.model;
    const std::size_t n = model.nodes();
    r.sys.v0[node] = speed * 0.6;
    r.sys.v0[n + node] = speed * 0.8;
    auto in = start(r, dynamics::IntegratorKind::verlet);
    const auto steps = static_cast<long long>(1000 / c.step);  // 7 τ: the node is free after 0.2 τ
    double vx_free = 0, vy_free = 0, t_free = 0, x_free = 0, y_free = 0;
    long long free_steps = 0;
    bool ballistic = true;
    const Trace tr = integrate(model, *in, steps, 1, [&](long long) {
      if (!(in->a()[node] == 0 && in->a()[n + node] == 0)) {
        free_steps = 0;
        return;
      }
      if (free_steps == 0) {
        vx_free = in->v()[node];
        vy_free = in->v()[n + node];
        x_free = in->q()[node];
        y_free = in->q()[n + node];
        t_free = in->t();
      }
      ++free_steps;
      ballistic = ballistic && in->v()[node] == vx_free && in->v()[n + node] == vy_free;
    });
    char what[64];
    std::snprintf(what, sizeof what, "%s, dt = %g × auto", c.irreversible ? "irreversible" : "reversible", c.step);
    EXPECT_TRUE(tr.finite);
    ASSERT_GT(free_steps, steps / 2) << what << ": the node did not leave within half the run";
    EXPECT_TRUE(ballistic) << what << ": the free node's velocity changed";
    const double dt_free = in->t() - t_free;
    EXPECT_NEAR(in->q()[node], x_free + vx_free * dt_free, 1e-9 * std::abs(in->q()[node]));
    EXPECT_NEAR(in->q()[n + node], y_free + vy_free * dt_free, 1e-9 * std::abs(in->q()[n + node]));
    const double kick = 0.5 * model.node_mass() * speed * speed;
    EXPECT_LE(tr.max_dev, c.tolerance * kick) << what;
    EXPECT_LE(tr.momentum, 1e-10);
    std::printf(
        "[measured] node flying off at 50 √a (%s): dt = %.3g τ, free after %lld steps with %.3g of its "
        "kinetic energy; max |E − E0| %.2e of the kick, momentum %.1e\n",
        what, r.setup.dt / kTau, steps - free_steps, (vx_free * vx_free + vy_free * vy_free) / (speed * speed),
        tr.max_dev / kick, tr.momentum);
  }
}

// ------------------------------------------------------------------------------------------ 10^6 steps
// A small undamped elastic sheet (4 × 4 nodes, periodic, at the stretch scene's (1.2, 3) with the
// default law: every bond in the Mooney-Rivlin branch, 16 widths below u_c) with thermal noise (0.02 √a),
// 10^6 steps of each integrator at rubber-run's automatic step for it (safety 0.5 of the bound set by a
// bond passing through the cut-off; the far field's ω·dt is then 0.093 for Verlet, 0.014 for gear5).
// Stated against the thermal KE0, per integrator:
//   Verlet: max |E − E0| 3.3e-4 (symplectic: a bounded oscillation of order (ω dt)²/8, tolerance 5e-3),
//           drift (mean of the last tenth − mean of the first tenth) 7e-8 (tolerance 1e-6);
//   gear5:  max |E − E0| 5.9e-6 (tolerance 1e-4), drift 1.2e-8 (tolerance 1e-6): not symplectic, but at
//           its own automatic step (6.5 times smaller) the drift stays far below Verlet's oscillation.
TEST(RubberStability, MillionStepsOfAnUndampedElasticLattice) {
  const auto m = sheet(4, 4);
  struct Case {
    dynamics::IntegratorKind kind;
    double fluctuation, drift;  // tolerances, of KE0
  };
  for (const Case c :
       {Case{dynamics::IntegratorKind::verlet, 5e-3, 1e-6}, Case{dynamics::IntegratorKind::gear5, 1e-4, 1e-6}}) {
    const std::string name(dynamics::name(c.kind));
    Rig r = make_rig(m, 1.2, 3, 0.02, "[integrator]\nkind = " + name + "\n");
    EXPECT_TRUE(r.setup.warnings.empty());
    auto in = start(r, c.kind);
    const Trace tr = integrate(*r.sys.model, *in, 1000000, 100);
    EXPECT_TRUE(tr.finite);
    const double fluct = tr.max_dev / tr.ke0, drift = tr.drift / tr.ke0;
    std::printf(
        "[measured] 10^6 steps, %s, dt = %.3g τ (ω_far dt = %.3g, %.0f τ): max |E − E0| %.2e of KE0, drift "
        "(last tenth − first tenth) %.2e, momentum %.1e\n",
        name.c_str(), r.setup.dt / kTau, r.setup.omega_far * r.setup.dt, 1e6 * r.setup.dt / kTau, fluct, drift,
        tr.momentum);
    EXPECT_LT(fluct, c.fluctuation) << name;
    EXPECT_LT(drift, c.drift) << name;
    EXPECT_LE(tr.momentum, 1e-10);
  }
}

}  // namespace
}  // namespace frac::rubber
