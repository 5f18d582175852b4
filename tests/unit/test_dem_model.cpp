// The polygon DEM as a whole (lib/dem/model, run, timestep, simulation; physics/polygon-dem.md §4-§8,
// validation E10): energy and momentum conservation of an isolated body, the energy ledger of every
// scene, the breaking rule on real beams, the physics switches, and the time-step bound.
// Meshes are random lattices (a = g, g = 1.07 cm as in the paper) of a few hundred cells.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/rng.hpp"
#include "core/scene.hpp"
#include "dem/beams.hpp"
#include "dem/contact_laws.hpp"
#include "dem/contact_search.hpp"
#include "dem/model.hpp"
#include "dem/run.hpp"
#include "dem/run_file.hpp"
#include "dem/scene.hpp"
#include "dem/simulation.hpp"
#include "dem/timestep.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/random_lattice.hpp"
#include "test_support.hpp"

namespace {

using frac::dem::Material;
using frac::dem::Model;
using frac::dem::Physics;
using frac::dynamics::IntegratorKind;
using frac::geometry::Vec2;
using frac::mesh::CellMesh;

constexpr double kPi = std::numbers::pi;
constexpr double kG = 0.0107;  // m, the paper's cell size (1100 cells in a 40 cm disc)

CellMesh rect_mesh(int nx, int ny, std::uint64_t seed) {
  frac::mesh::RandomLatticeOptions o;
  o.shape = "rect";
  o.nx = nx;
  o.ny = ny;
  o.width = nx * kG;
  o.height = ny * kG;
  o.seed = seed;
  return frac::mesh::make_random_lattice(o);
}

CellMesh disc_mesh(int cells, std::uint64_t seed) {
  frac::mesh::RandomLatticeOptions o;
  o.shape = "disc";
  o.cells = cells;
  o.diameter = 2 * std::sqrt(cells / kPi) * kG;
  o.seed = seed;
  return frac::mesh::make_random_lattice(o);
}

std::vector<double> reference_state(const CellMesh& mesh) {
  const std::size_t n = mesh.cells();
  std::vector<double> q(3 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    q[k] = mesh.centroid[k].x();
    q[n + k] = mesh.centroid[k].y();
  }
  return q;
}

// Σ m v, Σ m|v|, and the angular momentum about the origin Σ m (x v_y − y v_x) + I ω with its scale.
struct Momenta {
  Vec2 p;
  double p_scale, l, l_scale;
};
Momenta momenta(const Model& m, std::span<const double> q, std::span<const double> v) {
  const std::size_t n = m.bodies().n;
  Momenta r{Vec2(0, 0), 0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    const double mk = m.bodies().mass[k], ik = m.bodies().inertia[k];
    r.p += mk * Vec2(v[k], v[n + k]);
    r.p_scale += mk * std::hypot(v[k], v[n + k]);
    const double lk = mk * (q[k] * v[n + k] - q[n + k] * v[k]);
    r.l += lk + ik * v[2 * n + k];
    r.l_scale += std::abs(lk) + std::abs(ik * v[2 * n + k]);
  }
  return r;
}

// ------------------------------------------------------------------ isolated body

struct DriftResult {
  double offset;  // |E(10 dt) − E(0)|/E(0): the start transient
  double drift;   // max |E(t) − E(10 dt)|/E(0) over the rest of the run
  double total;   // max |E(t) − E(0)|/E(0)
  double momentum, angular;
  double omega_dt;
};

// Beams on, contacts off, no damping, no breaking; random small velocities (0.1 m/s, 10 rad/s: strains
// ~1e-4, far from breaking and from the nonlinear regime). Energy = kinetic + beam elastic energy.
// `jerk_start`: gear5 started with r3 = dt³/6·da/dt, da/dt = (∂a/∂q)·v by a central difference of the
// forces (instead of the usual r3 = r4 = r5 = 0), to show where the start transient comes from.
DriftResult isolated_body_drift(IntegratorKind kind, int steps, double dt, bool jerk_start = false) {
  const CellMesh mesh = rect_mesh(16, 13, 42);
  Material mat;  // Table 1
  Physics ph;
  ph.contacts = false;
  ph.breaking = false;
  Model model(mesh, mat, ph);
  const frac::dem::TimeStep ts = frac::dem::choose_time_step(mesh, mat, ph, kind, dt, 0.5, false);
  const std::size_t n = mesh.cells();
  const auto q0 = reference_state(mesh);
  std::vector<double> v0(3 * n);
  frac::Rng rng(7);
  for (std::size_t k = 0; k < n; ++k) {
    v0[k] = rng.uniform(-0.1, 0.1);
    v0[n + k] = rng.uniform(-0.1, 0.1);
    v0[2 * n + k] = rng.uniform(-10, 10);
  }
  auto in = frac::dynamics::make_integrator(kind);
  if (jerk_start) {
    const std::size_t d = 3 * n;
    std::vector<double> a(d), ap(d), am(d), qp(q0), qm(q0), jerk(d);
    const double eps = 1e-8;  // s: displacements v·eps ~ 1e-9 m, forces linear to ~1e-7 there
    for (std::size_t k = 0; k < d; ++k) {
      qp[k] += eps * v0[k];
      qm[k] -= eps * v0[k];
    }
    model.accelerations(0, qp, v0, ap);
    model.accelerations(0, qm, v0, am);
    for (std::size_t k = 0; k < d; ++k) jerk[k] = (ap[k] - am[k]) / (2 * eps);
    model.accelerations(0, q0, v0, a);
    dynamic_cast<frac::dynamics::Gear5&>(*in).start_exact(
        model, 0.0, dt, {q0, v0, a, jerk, std::vector<double>(d, 0.0), std::vector<double>(d, 0.0)});
  } else {
    in->start(model, 0.0, dt, q0, v0);
  }
  auto energy = [&] {
    const auto ke = model.kinetic_energy(in->v());
    return ke[0] + ke[1] + model.beams().energy(in->q());
  };
  const double e0 = energy();
  const Momenta m0 = momenta(model, in->q(), in->v());
  DriftResult r{0, 0, 0, 0, 0, ts.omega_max * dt};
  double e10 = e0;
  for (int s = 1; s <= steps; ++s) {
    in->step(model);
    if (s <= 10 || s % 10 == 0 || s == steps) {
      const double e = energy();
      if (s == 10) {
        e10 = e;
        r.offset = std::abs(e - e0) / e0;
      }
      if (s >= 10) r.drift = std::max(r.drift, std::abs(e - e10) / e0);
      r.total = std::max(r.total, std::abs(e - e0) / e0);
      const Momenta m = momenta(model, in->q(), in->v());
      r.momentum = std::max(r.momentum, (m.p - m0.p).norm() / m0.p_scale);
      r.angular = std::max(r.angular, std::abs(m.l - m0.l) / m0.l_scale);
    }
  }
  EXPECT_EQ(model.calls("contact"), 0);
  EXPECT_EQ(model.beams().intact_count(), model.beams().size());
  return r;
}

// Acceptance: gear5 at the paper's dt = 1e-6 s (ω_max·dt ≈ 0.1 on this sample), 10^4 steps: energy
// drift < 1e-4 relative (validation E10). The engine's usual start (r3 = r4 = r5 = 0) puts an offset into
// the energy during the first few steps, before any drift: the velocity r1/dt is off by O(dt²·da/dt),
// i.e. by O((ω dt)²) ≈ 1e-2 relative on the fastest modes, which hold a share of the energy. That offset
// is not a drift; it is reported, bounded by 1e-3, and shown to vanish (< 1e-5) when gear5 starts from
// the jerk. Linear momentum: conserved to 1e-10 relative to Σ m|v| (beam forces are equal and opposite
// and both schemes are linear in the accelerations, so only the rounding of Σ F enters, ~1e-16 per
// step). Angular momentum: exact in the force law (Q = (M_i + M_j)/l), approximate in the integrators
// (rotations are nonlinear in q): reported, and bounded by 1e-6. Verlet: reported; symplectic, so its
// energy error oscillates at O((ω dt)²) without drifting; bounded by 1e-2.
TEST(DemModel, IsolatedBodyConservesEnergyAndMomentum) {
  const DriftResult g = isolated_body_drift(IntegratorKind::gear5, 10000, 1e-6);
  const DriftResult j = isolated_body_drift(IntegratorKind::gear5, 10000, 1e-6, true);
  const DriftResult v = isolated_body_drift(IntegratorKind::verlet, 10000, 1e-6);
  std::printf(
      "[ drift    ] isolated body, 208 cells, 1e4 steps of 1e-6 s (omega_max dt = %.3f), relative to E(0):\n"
      "             gear5 (usual start): start offset %.2e, drift after it %.2e, total %.2e; momentum %.2e, "
      "angular momentum %.2e\n"
      "             gear5 (jerk start) : start offset %.2e, drift after it %.2e, total %.2e; momentum %.2e, "
      "angular momentum %.2e\n"
      "             verlet             : start offset %.2e, drift after it %.2e, total %.2e; momentum %.2e, "
      "angular momentum %.2e\n",
      g.omega_dt, g.offset, g.drift, g.total, g.momentum, g.angular, j.offset, j.drift, j.total, j.momentum, j.angular,
      v.offset, v.drift, v.total, v.momentum, v.angular);
  EXPECT_LT(g.drift, 1e-4);
  EXPECT_LT(g.offset, 1e-3);
  EXPECT_LT(j.total, 1e-4);
  EXPECT_LT(j.offset, 1e-5);
  EXPECT_LT(g.momentum, 1e-10);
  EXPECT_LT(v.momentum, 1e-10);
  EXPECT_LT(g.angular, 1e-6);
  EXPECT_LT(v.angular, 1e-6);
  EXPECT_LT(v.total, 1e-2);
}

// ------------------------------------------------------------------ scenes and the energy ledger

// data/scenes/ of the source tree, found from this file's path (tests/unit/ → ../../data/scenes).
std::string scene_path(const std::string& name) {
  const std::filesystem::path root = std::filesystem::path(__FILE__).parent_path().parent_path().parent_path();
  return (root / "data" / "scenes" / (name + ".ini")).string();
}

frac::dem::DemScene load_scene(const std::string& name, const std::vector<std::pair<std::string, std::string>>& set) {
  frac::Scene s = frac::Scene::load(scene_path(name));
  for (const auto& [k, v] : set) s.set(k, v);
  frac::dem::DemScene d = frac::dem::read_dem_scene(s);
  s.check_all_used();
  return d;
}

frac::dem::RunSummary run(const CellMesh& mesh, const frac::dem::DemScene& scene) {
  frac::dem::Simulation sim(mesh, scene);
  frac::Progress progress("test", true);
  return sim.run(progress);
}

struct SceneCase {
  std::string name;
  CellMesh mesh;
  std::vector<std::pair<std::string, std::string>> set;
};

// Acceptance: the energy balance (kinetic + beam elastic + work against contact, damping and friction +
// energy removed with broken beams − boundary work) stays at its initial value within 1% of the scale
// (the larger of the initial energy and the boundary work) in every scene, breaking, damping and
// friction on. Small meshes and short runs; the loaded scenes are driven fast (5 m/s) so that beams
// break within the run. Damping and friction rates γ_N = γ_T = 2e3 s^-1 (the scenes' γ_N: a contact
// damping ratio ζ ≈ γ_N/(2ω_c) ≈ 0.02), μ = 0.3. Their effective rates on the stiffest (rotational)
// modes stay far below the velocity-damping stability edge of gear5 (γ·dt = 0.163, see
// test_integrator); larger rates are the subject of AutoTimeStepIsStableWithDampingAndFriction.
TEST(DemModel, EnergyBalanceInEveryScene) {
  const std::vector<std::pair<std::string, std::string>> dissipative{
      {"physics.damping", "on"},    {"material.gamma_n", "2e3"}, {"physics.friction", "on"},
      {"material.friction", "0.3"}, {"material.gamma_t", "2e3"}, {"physics.breaking", "on"}};
  std::vector<SceneCase> cases{
      {"explosion", disc_mesh(300, 3), {{"stop.t_max", "5e-4"}}},
      {"impact", rect_mesh(24, 12, 4), {{"stop.t_max", "5e-4"}}},
      {"pulse", disc_mesh(300, 5), {{"stop.t_max", "2e-4"}}},
      {"uniaxial",
       rect_mesh(12, 20, 6),
       {{"stop.t_max", "1e-3"}, {"loading.boundary_speed", "5"}, {"loading.ramp", "1e-4"}}},
      {"uniaxial",
       rect_mesh(12, 20, 7),
       {{"stop.t_max", "1e-3"},
        {"loading.boundary_speed", "5"},
        {"loading.ramp", "1e-4"},
        {"loading.direction", "compression"}}},
      {"confined-compression",
       rect_mesh(12, 20, 8),
       {{"stop.t_max", "1e-3"}, {"loading.boundary_speed", "5"}, {"loading.ramp", "1e-4"}}},
  };
  for (auto& c : cases) {
    auto set = dissipative;
    if (c.name == "pulse") set.back().second = "off";  // the pulse scene watches elastic waves
    set.insert(set.end(), c.set.begin(), c.set.end());
    const auto scene = load_scene(c.name, set);
    const auto s = run(c.mesh, scene);
    const double rel = s.energy_error / s.energy_scale;
    std::printf(
        "[ ledger   ] %-22s %4zu cells: %6lld steps of %.3g s (%s), %5lld beams broken, scale %.4g J, "
        "max |balance - initial| = %.3g J = %.3f%%\n",
        c.name.c_str(), c.mesh.cells(), static_cast<long long>(s.steps), s.dt, s.stop_reason.c_str(),
        static_cast<long long>(s.broken), s.energy_scale, s.energy_error, 100 * rel);
    EXPECT_GT(s.energy_scale, 0) << c.name;
    EXPECT_LT(rel, 0.01) << c.name;
    if (c.name != "pulse") {
      EXPECT_GT(s.broken, 0) << c.name << ": the run should break beams";
    }
  }
}

// A run with energy to compare with reports its balance in %; one that starts at rest with no boundary work (a
// scale of 0) reports the error in joules, not a ratio to nothing.
TEST(DemModel, EnergyBalanceIsReportedAgainstWhatTheRunHad) {
  frac::dem::RunSummary s;
  s.energy_error = 0.5;
  s.energy_scale = 100;
  EXPECT_EQ(frac::dem::energy_balance_text(s), "energy balance within 0.5 %");
  s.energy_error = 2e-20;
  s.energy_scale = 0;
  EXPECT_EQ(frac::dem::energy_balance_text(s), "energy balance within 2e-20 J (no initial energy or boundary work)");
}

// The impact's projectile (physics/polygon-dem.md §8.4; loading.impact_width): on the paper's mesh one cell
// at the middle of the bottom edge; on a mesh of half the cell size, the cells whose centroids lie in the
// paper cell's square (impact_width = kG). Both carry the scene's 457 J exactly (the speed follows from
// the mass), all kicked cells fly straight into the block at one speed, and the finer projectile weighs
// about one paper cell (ρ h kG²; ±50 %: four Voronoi centroids sampling a square, whose bottom row is
// clipped by the edge).
TEST(DemModel, ImpactProjectileKeepsItsEnergyOnAFinerMesh) {
  frac::mesh::RandomLatticeOptions o;
  o.shape = "rect";
  o.nx = 48, o.ny = 24, o.width = 24 * kG, o.height = 12 * kG, o.seed = 9;
  const CellMesh fine = frac::mesh::make_random_lattice(o);
  const auto coarse_scene = load_scene("impact", {});
  const auto fine_scene =
      load_scene("impact", {{"loading.impact_width", std::to_string(kG)}, {"integrator.dt", "5e-7"}});
  for (const auto& [mesh, scene] : {std::pair{rect_mesh(24, 12, 9), coarse_scene}, std::pair{fine, fine_scene}}) {
    const frac::dem::Simulation sim(mesh, scene);
    const auto kick = frac::dem::kick_report(sim);
    const std::size_t n = mesh.cells();
    double mass = 0;
    for (std::size_t k : sim.setup.kicked) {
      EXPECT_EQ(sim.v0[k], 0.0);
      EXPECT_DOUBLE_EQ(sim.v0[n + k], kick.mean_speed);
      mass += sim.model.bodies().mass[k];
    }
    EXPECT_EQ(kick.cells, sim.setup.kicked.size());
    EXPECT_NEAR(kick.kinetic_energy, 457.0, 1e-9 * 457);
    EXPECT_NEAR(kick.momentum_over_scale, 1.0, 1e-12);  // all along +y
    if (scene.loading.impact_width > 0) {
      EXPECT_GE(kick.cells, 2u);
      const double paper_cell = scene.material.density * scene.material.thickness * kG * kG;
      EXPECT_GT(mass, 0.5 * paper_cell);
      EXPECT_LT(mass, 1.5 * paper_cell);
    } else {
      EXPECT_EQ(kick.cells, 1u);
    }
  }
}

// The model has no length scale (strain thresholds, moduli, no damping): a block twice as large, on the same
// mesh scaled by 2 (exact in binary floating point), hit with four times the energy (the same energy per mass)
// and run twice as long at twice the time step, breaks exactly the same beams. So a larger block of the
// same cells at the same specific energy is the same experiment as finer cells in the same block.
TEST(DemModel, ImpactOnABlockTwiceAsLargeBreaksTheSameBeams) {
  const auto text = [](double v) { return (std::ostringstream() << std::setprecision(17) << v).str(); };
  std::vector<std::vector<std::uint8_t>> intact;
  for (double scale : {1.0, 2.0}) {
    frac::mesh::RandomLatticeOptions o;
    o.shape = "rect";
    o.nx = 20, o.ny = 10, o.width = scale * 20 * kG, o.height = scale * 10 * kG, o.seed = 12;
    const auto scene = load_scene("impact", {{"loading.impact_energy", text(457 * scale * scale)},
                                             {"integrator.dt", text(5e-7 * scale)},
                                             {"stop.t_max", text(4e-4 * scale)}});
    const CellMesh mesh = frac::mesh::make_random_lattice(o);  // the simulation keeps a reference
    frac::dem::Simulation sim(mesh, scene);
    frac::Progress progress("test", true);
    const auto s = sim.run(progress);
    EXPECT_GT(s.broken, 20) << "the impact should break beams";
    const auto flags = sim.model.beams().intact();
    intact.emplace_back(flags.begin(), flags.end());
  }
  EXPECT_EQ(intact[0], intact[1]);
}

// ------------------------------------------------------------------ breaking on real beams

// Two unit-ish squares side by side sharing a side: one beam, l0 = S = s.
CellMesh two_squares(double s) {
  CellMesh m;
  for (int k = 0; k < 2; ++k) {
    for (const Vec2& v : {Vec2(-s / 2, -s / 2), Vec2(s / 2, -s / 2), Vec2(s / 2, s / 2), Vec2(-s / 2, s / 2)})
      m.vertex.push_back(v);
    m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
    m.centroid.emplace_back(k * s, 0.0);
    m.area.push_back(s * s);
    m.second_moment.push_back(s * s * s * s / 6);
  }
  m.beam.push_back({0, 1});
  m.beam_length.push_back(s);
  m.beam_section.push_back(s);
  m.shape = "rect";
  m.spacing = s;
  m.bounds = {-s / 2, -s / 2, 1.5 * s, s / 2};
  return m;
}

// State of the pair: j at (s(1 + strain), 0) turned by phi_j, i at the origin turned by phi_i.
std::vector<double> pair_state(double s, double strain, double phi_i, double phi_j) {
  return {0.0, s * (1 + strain), 0.0, 0.0, phi_i, phi_j};
}

// Breaks the beam of a fresh pair at the given state; returns the mode (0 if it holds).
int break_at(double strain, double phi_i, double phi_j) {
  const double s = 0.01;
  const CellMesh mesh = two_squares(s);
  Material mat;
  Model model(mesh, mat, Physics{});
  std::vector<frac::dem::BeamBreak> broken;
  const auto q = pair_state(s, strain, phi_i, phi_j);
  model.beams().break_beams(q, mat.t_eps, mat.t_theta, broken);
  EXPECT_EQ(model.beams().intact_count(), broken.empty() ? 1u : 0u);
  return broken.empty() ? 0 : broken[0].mode;
}

TEST(DemModel, BreakingOfARealBeam) {
  const Material mat;
  const double te = mat.t_eps, tt = mat.t_theta;
  EXPECT_NEAR(tt, 4 * kPi / 180, 1e-15);
  // Pulled past t_ε: breaks by stretching; just below: holds.
  EXPECT_EQ(break_at(1.001 * te, 0, 0), 1);
  EXPECT_EQ(break_at(0.999 * te, 0, 0), 0);
  // Compressed by any amount, however bent: never.
  for (double c : {1e-9, 1e-3, 0.03, 0.1, 0.5, 0.9})
    for (double phi : {0.0, 2 * tt, 1.0, 3.0}) EXPECT_EQ(break_at(-c, phi, -phi), 0) << c << " " << phi;
  // Bending alone, past t_Θ, on a barely stretched beam (ε = 1e-9: (ε/t_ε)² ~ 1e-15): breaks by bending;
  // just below t_Θ: holds; the same bending on a barely compressed beam: holds.
  EXPECT_EQ(break_at(1e-9, 1.001 * tt, 0), 2);
  EXPECT_EQ(break_at(1e-9, 0, -1.001 * tt), 2);
  EXPECT_EQ(break_at(1e-9, 0.999 * tt, 0.999 * tt), 0);
  EXPECT_EQ(break_at(-1e-9, 1.001 * tt, 0), 0);
  EXPECT_EQ(break_at(-1e-9, 10 * tt, -10 * tt), 0);
  // Bending relative to the current axis: the pair turned rigidly by 1 rad and stretched 2.9% holds.
  {
    const double s = 0.01, w = 1.0, l = s * 1.029;
    const CellMesh mesh = two_squares(s);
    Model model(mesh, mat, Physics{});
    std::vector<frac::dem::BeamBreak> broken;
    const std::vector<double> q{0.0, l * std::cos(w), 0.0, l * std::sin(w), w, w};
    model.beams().break_beams(q, te, tt, broken);
    EXPECT_TRUE(broken.empty());
  }
}

TEST(DemModel, BrokenBeamsStayBrokenAndCarryNoForce) {
  const double s = 0.01;
  const CellMesh mesh = two_squares(s);
  Material mat;
  Physics ph;
  ph.contacts = false;
  Model model(mesh, mat, ph);
  std::vector<frac::dem::BeamBreak> broken;
  const auto stretched = pair_state(s, 0.05, 0, 0);
  model.beams().break_beams(stretched, mat.t_eps, mat.t_theta, broken);
  ASSERT_EQ(broken.size(), 1u);
  // The energy it held: ½ α (l − l0)².
  const double alpha = model.beams().stiffness(0).alpha;
  EXPECT_NEAR(broken[0].energy, 0.5 * alpha * (0.05 * s) * (0.05 * s), 1e-12 * broken[0].energy);
  // Back to the reference state, then stretched again: no force, no energy, no second break.
  std::vector<double> a(6);
  model.accelerations(0, stretched, std::vector<double>(6, 0.0), a);
  for (double x : a) EXPECT_EQ(x, 0.0);
  EXPECT_EQ(model.beams().energy(stretched), 0.0);
  const auto rest = pair_state(s, 0, 0, 0);
  model.beams().break_beams(rest, mat.t_eps, mat.t_theta, broken);
  model.beams().break_beams(stretched, mat.t_eps, mat.t_theta, broken);
  EXPECT_EQ(broken.size(), 1u);
  EXPECT_EQ(model.beams().intact()[0], 0);
}

TEST(DemModel, PullingAPairApartBreaksItAtTheThreshold) {
  // Dynamic: two squares flying apart at 30 m/s relative (kinetic energy well above ½ α (t_ε l0)²);
  // the beam must break on the first step whose strain passes t_ε, i.e. at a strain in
  // [t_ε, t_ε + v_rel·dt/l0] (the breaking pass runs after every step).
  const double s = 0.01, dt = 1e-8, vrel = 30;
  const CellMesh mesh = two_squares(s);
  Material mat;
  Physics ph;
  ph.contacts = false;
  Model model(mesh, mat, ph);
  auto in = frac::dynamics::make_integrator(IntegratorKind::gear5);
  in->start(model, 0.0, dt, reference_state(mesh), std::vector<double>{-vrel / 2, vrel / 2, 0, 0, 0, 0});
  std::vector<frac::dem::BeamBreak> broken;
  double strain = 0;
  for (int step = 0; step < 100000 && broken.empty(); ++step) {
    in->step(model);
    strain = (in->q()[1] - in->q()[0]) / s - 1;
    model.beams().break_beams(in->q(), mat.t_eps, mat.t_theta, broken);
  }
  ASSERT_EQ(broken.size(), 1u);
  EXPECT_EQ(broken[0].mode, 1);
  EXPECT_GE(strain, mat.t_eps);
  EXPECT_LE(strain, mat.t_eps + vrel * dt / s);
}

// The time step must be stable for the damping and friction a scene names, not only for its
// stiffnesses. Gear5 is unstable for velocity-dependent forces once γ_eff·dt > 0.163 (test_integrator,
// DampingStabilityEdges), where γ_eff is the rate at which a dashpot slows the relative motion: for two
// equal squares in face contact γ_N along the normal, and about 2.5 γ_T along the tangent (translation
// plus the rotation the tangential force at R drives: 1 + m_eff (r_i²/I_i + r_j²/I_j) = 1 + ½·2·1.5).
// A minimal case: two bonded squares (beams on, breaking off), j moving into i at 1 m/s while sliding
// along it at 1 m/s, dt = auto. With γ_N·dt = 0.25 or γ_T·dt = 0.1 (γ_eff·dt ≈ 0.25) the auto step must
// either come out smaller or the run must keep its energy balance within 1%: whatever dt the check
// accepts has to be stable.
double two_square_balance(bool friction, double gamma_dt, double* dt_out) {
  const double s = 0.01;
  const CellMesh mesh = two_squares(s);
  frac::dem::DemScene sc;
  sc.physics.breaking = false;
  sc.physics.laws = {"contact", friction ? "friction" : "damping"};
  sc.material.friction = 10;  // viscous regime of the friction law: the Coulomb cap never acts
  sc.stop.t_max = 3e-4;
  sc.integrator.dt = 0;  // auto
  const double dt0 = frac::dem::Simulation(mesh, sc).time_step.dt;
  (friction ? sc.material.gamma_t : sc.material.gamma_n) = gamma_dt / dt0;
  frac::dem::Simulation sim(mesh, sc);
  *dt_out = sim.time_step.dt;
  sim.v0[1] = -1.0;  // j toward i
  sim.v0[3] = 1.0;   // j sliding along i
  frac::Progress progress("test", true);
  const auto r = sim.run(progress);
  return r.energy_error / r.energy_scale;
}

TEST(DemModel, AutoTimeStepIsStableWithDampingAndFriction) {
  double dt_mild = 0, dt_damp = 0, dt_fric = 0;
  const double mild = two_square_balance(true, 0.01, &dt_mild);  // γ_eff·dt ≈ 0.025: stable
  const double damp = two_square_balance(false, 0.25, &dt_damp);
  const double fric = two_square_balance(true, 0.1, &dt_fric);
  std::printf(
      "[ timestep ] two squares, dt = auto: friction gamma_t dt = 0.01 -> dt %.3g s, balance error %.2e; "
      "damping gamma_n dt0 = 0.25 -> dt %.3g s, error %.2e; friction gamma_t dt0 = 0.1 -> dt %.3g s, error "
      "%.2e (of the initial energy)\n",
      dt_mild, mild, dt_damp, damp, dt_fric, fric);
  EXPECT_LT(mild, 0.01);
  EXPECT_LT(damp, 0.01) << "dt = auto is unstable with normal damping (γ_N·dt = " << 0.25 * dt_damp / dt_mild
                        << "); the time-step check ignores γ_N";
  EXPECT_LT(fric, 0.01) << "dt = auto is unstable with friction (γ_T·dt = " << 0.1 * dt_fric / dt_mild
                        << "); the time-step check ignores γ_T";
}

// ------------------------------------------------------------------ physics switches

// Steps two simulations side by side (the run's loop: step, then the breaking pass if on) and reports the
// first step at which their states, forces or broken beams differ in any bit (−1 if none), and how many
// beams the first one broke.
struct Comparison {
  long first_difference;
  std::size_t broken;    // beams the first simulation broke
  std::size_t contacts;  // most contacts the second one saw at an evaluation
};
Comparison compare(const CellMesh& mesh, const frac::dem::DemScene& a, const frac::dem::DemScene& b, int steps) {
  frac::dem::Simulation sa(mesh, a), sb(mesh, b);
  EXPECT_EQ(sa.time_step.dt, sb.time_step.dt);
  sa.integrator->start(sa.model, 0, sa.time_step.dt, sa.q0, sa.v0);
  sb.integrator->start(sb.model, 0, sb.time_step.dt, sb.q0, sb.v0);
  std::vector<frac::dem::BeamBreak> ba, bb;
  std::size_t contacts = 0;
  auto same = [](std::span<const double> x, std::span<const double> y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
  };
  for (int s = 1; s <= steps; ++s) {
    sa.integrator->step(sa.model);
    sb.integrator->step(sb.model);
    if (a.physics.breaking) sa.model.beams().break_beams(sa.integrator->q(), a.material.t_eps, a.material.t_theta, ba);
    if (b.physics.breaking) sb.model.beams().break_beams(sb.integrator->q(), b.material.t_eps, b.material.t_theta, bb);
    bool equal = same(sa.integrator->q(), sb.integrator->q()) && same(sa.integrator->v(), sb.integrator->v()) &&
                 same(sa.model.forces(), sb.model.forces()) && ba.size() == bb.size();
    for (std::size_t k = 0; equal && k < ba.size(); ++k) equal = ba[k].beam == bb[k].beam;
    contacts = std::max(contacts, sb.model.contacts().size());
    if (!equal) return {s, ba.size(), contacts};
  }
  return {-1, ba.size(), contacts};
}

// The explosion of a 200-cell disc, 800 steps of 1e-6 s: the kick, contacts everywhere, beams breaking
// from the first steps, damping on.
constexpr int kSteps = 800;
const std::vector<std::pair<std::string, std::string>> kBusy{
    {"stop.t_max", "8e-4"}, {"physics.damping", "on"}, {"material.gamma_n", "2e3"}};

std::vector<std::pair<std::string, std::string>> with(std::vector<std::pair<std::string, std::string>> base,
                                                      const std::vector<std::pair<std::string, std::string>>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

TEST(DemModel, TermsThatAreOffAreNeverCalled) {
  const CellMesh mesh = disc_mesh(200, 9);
  {
    const auto scene = load_scene("explosion", with(kBusy, {{"stop.t_max", "2e-4"}}));  // friction off (file)
    ASSERT_FALSE(scene.physics.has("friction"));
    frac::dem::Simulation sim(mesh, scene);
    frac::Progress progress("test", true);
    const auto s = sim.run(progress);
    EXPECT_EQ(sim.model.calls("friction"), 0);
    EXPECT_EQ(sim.model.calls("contact"), s.steps + 1);  // one evaluation per step + the start
    EXPECT_EQ(sim.model.calls("damping"), s.steps + 1);
    EXPECT_EQ(sim.model.calls("beams"), s.steps + 1);
  }
  {
    const auto scene = load_scene("explosion", {{"stop.t_max", "2e-4"}, {"physics.contacts", "off"}});
    frac::dem::Simulation sim(mesh, scene);
    frac::Progress progress("test", true);
    const auto s = sim.run(progress);
    EXPECT_EQ(sim.model.calls("contact"), 0);
    EXPECT_EQ(sim.model.calls("damping"), 0);
    EXPECT_EQ(sim.model.calls("friction"), 0);
    EXPECT_EQ(sim.model.calls("beams"), s.steps + 1);
    EXPECT_EQ(sim.model.contacts().size(), 0u);
  }
  {
    const auto scene =
        load_scene("explosion", {{"stop.t_max", "2e-4"}, {"physics.beams", "off"}, {"physics.breaking", "off"}});
    frac::dem::Simulation sim(mesh, scene);
    frac::Progress progress("test", true);
    sim.run(progress);
    EXPECT_EQ(sim.model.calls("beams"), 0);
  }
  // A switch that needs another is refused.
  EXPECT_THROW(load_scene("explosion", {{"physics.contacts", "off"}, {"physics.friction", "on"}}), frac::UsageError);
  EXPECT_THROW(load_scene("explosion", {{"physics.beams", "off"}}), frac::UsageError);  // breaking on
}

// Friction on with μ = 0 (γ_T > 0, so only the Coulomb cap makes it zero) against friction off: the
// friction term then adds exact zeros (min(·, 0) = 0, and ±0 added to a force sum that started at +0
// leaves every bit unchanged), so the trajectories must agree in every bit, step by step.
TEST(DemModel, FrictionWithZeroMuEqualsFrictionOff) {
  const CellMesh mesh = disc_mesh(200, 9);
  const auto off = load_scene("explosion", kBusy);
  const auto on = load_scene(
      "explosion", with(kBusy, {{"physics.friction", "on"}, {"material.friction", "0"}, {"material.gamma_t", "2e3"}}));
  const Comparison c = compare(mesh, off, on, kSteps);
  EXPECT_EQ(c.first_difference, -1);
  EXPECT_GT(c.broken, 10u) << "the run should break beams";
  EXPECT_GT(c.contacts, 100u) << "the run should have contacts";
  // A nonzero μ does change it (the comparison can see friction at all).
  const auto mu =
      load_scene("explosion",
                 with(kBusy, {{"physics.friction", "on"}, {"material.friction", "0.3"}, {"material.gamma_t", "2e3"}}));
  EXPECT_NE(compare(mesh, off, mu, kSteps).first_difference, -1);
}

TEST(DemModel, DampingWithZeroGammaEqualsDampingOff) {
  const CellMesh mesh = disc_mesh(200, 9);
  const auto off = load_scene("explosion", {{"stop.t_max", "8e-4"}});
  const auto on =
      load_scene("explosion", {{"stop.t_max", "8e-4"}, {"physics.damping", "on"}, {"material.gamma_n", "0"}});
  EXPECT_EQ(compare(mesh, off, on, kSteps).first_difference, -1);
  const auto some =
      load_scene("explosion", {{"stop.t_max", "8e-4"}, {"physics.damping", "on"}, {"material.gamma_n", "1e3"}});
  EXPECT_NE(compare(mesh, off, some, kSteps).first_difference, -1);
}

// Contacts on with Y = 0 against contacts off. With Y = 0 the elastic term computes −0·A·h/L_c = ∓0 for
// every overlapping pair and adds those zeros at R (torques (R − c) × (±0) = ±0): as above, every bit of
// the forces is unchanged. The auto time step is the same too (the overlap stiffness Y·h·S/L_c adds 0
// to the axial stiffness in max_eigenfrequency). Checked with gear5 and Verlet, and with dt = auto. (A scene
// refuses a modulus of 0, which no solid has: the model's material is set directly.)
TEST(DemModel, ContactsWithZeroModulusEqualContactsOff) {
  const CellMesh mesh = disc_mesh(200, 9);
  for (const auto& [integrator, dt] :
       {std::pair{"gear5", "1e-6"}, std::pair{"verlet", "1e-6"}, std::pair{"gear5", "auto"}}) {
    const std::vector<std::pair<std::string, std::string>> base{
        {"stop.t_max", "8e-4"}, {"integrator.kind", integrator}, {"integrator.dt", dt}};
    const auto off = load_scene("explosion", with(base, {{"physics.contacts", "off"}}));
    auto on = load_scene("explosion", base);
    on.material.grain_modulus = 0;
    const Comparison c = compare(mesh, off, on, kSteps);
    EXPECT_EQ(c.first_difference, -1) << integrator << ", dt = " << dt;
    // The comparison saw overlaps (with Y = 0 nothing keeps the cells apart).
    EXPECT_GT(c.contacts, 100u) << integrator << ", dt = " << dt;
  }
  // With a nonzero modulus the trajectory differs.
  const auto off = load_scene("explosion", {{"stop.t_max", "8e-4"}, {"physics.contacts", "off"}});
  const auto on = load_scene("explosion", {{"stop.t_max", "8e-4"}});
  EXPECT_NE(compare(mesh, off, on, kSteps).first_difference, -1);
}

// Breaking on with thresholds no beam reaches (t_ε = t_Θ = 1e300) against breaking off: the same bits,
// and with breaking off the thresholds do nothing however small (the pass is not run: no beam breaks).
TEST(DemModel, BreakingWithUnreachableThresholdsEqualsBreakingOff) {
  const CellMesh mesh = disc_mesh(200, 9);
  const auto off = load_scene("explosion", {{"stop.t_max", "8e-4"}, {"physics.breaking", "off"}});
  const auto on =
      load_scene("explosion", {{"stop.t_max", "8e-4"}, {"material.t_eps", "1e300"}, {"material.t_theta_deg", "1e300"}});
  EXPECT_EQ(compare(mesh, off, on, kSteps).first_difference, -1);
  const auto brittle_off = load_scene("explosion", {{"stop.t_max", "2e-4"},
                                                    {"physics.breaking", "off"},
                                                    {"material.t_eps", "1e-9"},
                                                    {"material.t_theta_deg", "1e-9"}});
  frac::dem::Simulation sim(mesh, brittle_off);
  frac::Progress progress("test", true);
  EXPECT_EQ(sim.run(progress).broken, 0);
  EXPECT_EQ(sim.model.beams().intact_count(), sim.model.beams().size());
  const auto brittle_on =
      load_scene("explosion", {{"stop.t_max", "2e-4"}, {"material.t_eps", "1e-9"}, {"material.t_theta_deg", "1e-9"}});
  frac::dem::Simulation sim_on(mesh, brittle_on);
  EXPECT_GT(sim_on.run(progress).broken, 100);
}

// Beams on with E = 0 against beams off (breaking off in both): beam_stiffness gives α = β = δ = 0, so
// every beam adds ±0 to the force sums (unchanged bits, as above) and nothing to the time-step bound.
// (Before beam_stiffness special-cased E = 0, δ = β(b/c + 1/3) was 0·∞/∞ = NaN and the run stopped.) The
// material is set directly, as above.
TEST(DemModel, BeamsWithZeroModulusEqualBeamsOff) {
  const CellMesh mesh = disc_mesh(200, 9);
  const std::vector<std::pair<std::string, std::string>> base{{"stop.t_max", "8e-4"}, {"physics.breaking", "off"}};
  const auto off = load_scene("explosion", with(base, {{"physics.beams", "off"}}));
  auto on = load_scene("explosion", base);
  on.material.beam_modulus = 0;
  const Comparison c = compare(mesh, off, on, kSteps);
  EXPECT_EQ(c.first_difference, -1);
  EXPECT_GT(c.contacts, 100u);
  const auto stiff = load_scene("explosion", base);
  EXPECT_NE(compare(mesh, off, stiff, kSteps).first_difference, -1);
}

// ------------------------------------------------------------------ the time step

TEST(DemModel, TimeStepAboveTheBoundIsRefused) {
  const CellMesh mesh = rect_mesh(12, 12, 10);
  Material mat;
  Physics ph;
  for (IntegratorKind kind : {IntegratorKind::gear5, IntegratorKind::verlet}) {
    const auto ts = frac::dem::choose_time_step(mesh, mat, ph, kind, 0, 0.5, false);
    EXPECT_DOUBLE_EQ(ts.dt, 0.5 * ts.bound);
    EXPECT_DOUBLE_EQ(ts.bound, frac::dynamics::stability_limit(kind) / ts.omega_max);
    // Below the bound: accepted as given.
    EXPECT_EQ(frac::dem::choose_time_step(mesh, mat, ph, kind, 0.99 * ts.bound, 0.5, false).dt, 0.99 * ts.bound);
    // Above: UsageError with the bound in the message (as the message prints it: 3 significant digits).
    std::ostringstream bound;
    bound.precision(3);
    bound << ts.bound;
    try {
      frac::dem::choose_time_step(mesh, mat, ph, kind, 1.01 * ts.bound, 0.5, false);
      ADD_FAILURE() << "dt above the bound accepted";
    } catch (const frac::UsageError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(bound.str()), std::string::npos) << what << " (bound " << bound.str() << ")";
      EXPECT_NE(what.find("stability bound"), std::string::npos) << what;
    }
    // The explicit override.
    EXPECT_EQ(frac::dem::choose_time_step(mesh, mat, ph, kind, 1.01 * ts.bound, 0.5, true).dt, 1.01 * ts.bound);
  }
  // Through the scene: the Simulation refuses it before anything runs.
  const auto scene = load_scene("explosion", {{"integrator.dt", "1e-4"}});
  EXPECT_THROW(frac::dem::Simulation(disc_mesh(100, 1), scene), frac::UsageError);
}

// The bound rests on ω_max from power iteration (raised by 2%). Against a dense eigensolver on a small
// sample (beams only, the stiffness matrix by central differences of the model's forces about the
// reference state): ω_max must not be below the true largest eigenfrequency (else the bound would be
// unsafe) and not more than 3% above it (the 2% margin plus the power iteration's 1e-6 tolerance on λ).
// Finite differences: the forces are linear about the reference state up to O(h), h = 1e-9·g, so K
// is good to ~1e-7 relative.
TEST(DemModel, MaxEigenfrequencyAgainstDenseSolver) {
  for (std::uint64_t seed : {11u, 12u}) {
    const CellMesh mesh = rect_mesh(7, 6, seed);
    Material mat;
    Physics ph;
    ph.contacts = false;
    ph.breaking = false;
    Model model(mesh, mat, ph);
    const std::size_t n = mesh.cells(), d = 3 * n;
    const auto q0 = reference_state(mesh);
    const std::vector<double> v(d, 0.0);
    std::vector<double> a(d);
    Eigen::MatrixXd K(d, d);
    for (std::size_t c = 0; c < d; ++c) {
      const double h = 1e-9 * kG;
      auto qp = q0, qm = q0;
      qp[c] += h;
      qm[c] -= h;
      model.accelerations(0, qp, v, a);
      const std::vector<double> fp(model.forces().begin(), model.forces().end());
      model.accelerations(0, qm, v, a);
      for (std::size_t r = 0; r < d; ++r) K(r, c) = -(fp[r] - model.forces()[r]) / (2 * h);
    }
    Eigen::VectorXd inv_sqrt_m(d);
    for (std::size_t k = 0; k < n; ++k) {
      inv_sqrt_m[k] = inv_sqrt_m[n + k] = 1 / std::sqrt(model.bodies().mass[k]);
      inv_sqrt_m[2 * n + k] = 1 / std::sqrt(model.bodies().inertia[k]);
    }
    const Eigen::MatrixXd D = inv_sqrt_m.asDiagonal() * (0.5 * (K + K.transpose())) * inv_sqrt_m.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(D, Eigen::EigenvaluesOnly);
    const double omega_true = std::sqrt(es.eigenvalues().maxCoeff());
    const double omega = frac::dem::max_eigenfrequency(mesh, mat, ph);
    std::printf("[ timestep ] %zu cells: omega_max = %.5g rad/s, dense solver %.5g rad/s (ratio %.4f)\n", n, omega,
                omega_true, omega / omega_true);
    EXPECT_GE(omega, omega_true);
    EXPECT_LE(omega, 1.03 * omega_true);
  }
}

// ------------------------------------------------------------------ integrator.start (issue 7 §1)

// The scene key integrator.start on the smooth problem (the pulse scene with contacts off: beams only,
// no breaking, damping or friction) of a 100-cell disc, to T = 40 steps at the gear5 bound. Final positions
// at 2^0 and 2^-1 of the bound against gear5-exact at 2^-4: with the usual start the error halves twice
// per halving of dt (order 2), with integrator.start = exact five times (order 5; pipelines/accuracy-cost.mk
// measures 5.08 on the 1100-cell disc). The exact start costs a few dozen force evaluations, reported;
// Verlet accepts the key and runs exactly as without it.
TEST(DemModel, ExactStartMakesGear5FifthOrderOnTheSmoothProblem) {
  const CellMesh mesh = disc_mesh(100, 3);
  const long long n0 = 40;
  auto scene_for = [&](const std::string& kind, const std::string& start, double dt, long long steps) {
    std::ostringstream text;
    text.precision(17);
    text << dt;
    return load_scene("pulse", {{"physics.contacts", "off"},
                                {"integrator.kind", kind},
                                {"integrator.start", start},
                                {"integrator.dt", text.str()},
                                {"stop.t_max", "1"},
                                {"stop.max_steps", std::to_string(steps)}});
  };
  const double bound = frac::dem::Simulation(mesh, scene_for("gear5", "zero", 1e-9, 1)).time_step.bound;
  // Final positions (x, y) after n0·2^level steps of bound/2^level: every run ends at the same time.
  auto final_q = [&](const std::string& kind, const std::string& start, int level, int* evaluations = nullptr) {
    const frac::dem::DemScene d = scene_for(kind, start, 0.999 * bound / (1 << level), n0 << level);
    EXPECT_EQ(d.integrator.start,
              start == "exact" ? frac::dynamics::StartKind::exact : frac::dynamics::StartKind::zero);
    frac::dem::Simulation sim(mesh, d);
    frac::Progress progress("test", true);
    const auto summary = sim.run(progress);
    EXPECT_EQ(summary.steps, n0 << level);
    if (evaluations) *evaluations = summary.start_evaluations;
    const auto q = sim.integrator->q();
    return std::vector<double>(q.begin(), q.begin() + 2 * static_cast<std::ptrdiff_t>(mesh.cells()));
  };
  auto rms = [](const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(2 * s / static_cast<double>(a.size()));
  };
  int evaluations = 0;
  const auto ref = final_q("gear5", "exact", 4, &evaluations);
  const double z0 = rms(final_q("gear5", "zero", 0), ref), z1 = rms(final_q("gear5", "zero", 1), ref);
  const double e0 = rms(final_q("gear5", "exact", 0), ref), e1 = rms(final_q("gear5", "exact", 1), ref);
  const double pz = std::log2(z0 / z1), pe = std::log2(e0 / e1);
  std::printf(
      "[ start    ] pulse, beams only, 100 cells: gear5 zero start %.3g -> %.3g m (order %.2f), exact start "
      "%.3g -> %.3g m (order %.2f); the exact start took %d force evaluations\n",
      z0, z1, pz, e0, e1, pe, evaluations);
  EXPECT_NEAR(pz, 2.0, 0.3);
  EXPECT_NEAR(pe, 5.0, 0.6);
  EXPECT_LT(e0, 1e-2 * z0);
  EXPECT_GT(evaluations, 0);
  EXPECT_LE(evaluations, 150);
  // Verlet: the key changes nothing.
  EXPECT_EQ(final_q("verlet", "exact", 0), final_q("verlet", "zero", 0));
  // A value it does not know is refused, naming the key.
  try {
    (void)scene_for("gear5", "taylor", 1e-9, 1);
    ADD_FAILURE() << "integrator.start = taylor accepted";
  } catch (const frac::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("integrator.start"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// The beam forces on every cell equal the loop over the intact beams in beam order (F on i, −F and τ_j on
// j), bit for bit, with the beam law of beam.hpp: after some beams broke, too.
// A non-finite force is traced to the first term that made it and to a coordinate where it is not finite,
// on one and on two threads (400 cells: the per-coordinate loops run on the threads).
TEST(DemModel, NonFiniteForceIsTracedToItsTerm) {
  const CellMesh mesh = disc_mesh(400, 3);
  const std::size_t n = mesh.cells(), bad = n / 2;
  for (const int threads : {1, 2}) {
    const frac::test::ThreadCount thread_count(threads);
    Material mat;
    mat.gamma_n = 1000;
    Physics ph;
    ph.laws = {"contact", "damping"};
    // Squeezed by 1 % about the origin: neighbours overlap, so every contact term has work.
    auto q = reference_state(mesh);
    for (std::size_t k = 0; k < 2 * n; ++k) q[k] *= 0.99;
    std::vector<double> v(3 * n, 0.0), a(3 * n);
    {
      Model model(mesh, mat, ph);  // all finite
      model.accelerations(0, q, v, a);
      EXPECT_EQ(model.non_finite_term(), "");
      EXPECT_GT(model.contacts().size(), n);
    }
    {
      Model model(mesh, mat, ph);  // a turned-to-NaN cell: its beams (the first term) go NaN
      auto qb = q;
      qb[2 * n + bad] = std::numeric_limits<double>::quiet_NaN();
      model.accelerations(0, qb, v, a);
      EXPECT_EQ(model.non_finite_term(), "beams") << threads << " threads";
      EXPECT_FALSE(std::isfinite(model.forces()[model.non_finite_index()]));
    }
    {
      Model model(mesh, mat, ph);  // a NaN velocity: the positions are finite, only the damping sees it
      auto vb = v;
      vb[bad] = std::numeric_limits<double>::quiet_NaN();
      model.accelerations(0, q, vb, a);
      EXPECT_EQ(model.non_finite_term(), "damping") << threads << " threads";
      EXPECT_FALSE(std::isfinite(model.forces()[model.non_finite_index()]));
      // The first such coordinate: the cell's own, or that of a cell in contact with it (the opposite force).
      const std::size_t cell = model.non_finite_index() % n;
      bool touching = cell == bad;
      const auto& c = model.contacts();
      for (std::size_t k = 0; k < c.size(); ++k)
        touching |= (static_cast<std::size_t>(c.i[k]) == cell && static_cast<std::size_t>(c.j[k]) == bad) ||
                    (static_cast<std::size_t>(c.j[k]) == cell && static_cast<std::size_t>(c.i[k]) == bad);
      EXPECT_TRUE(touching) << "cell " << cell;
    }
  }
}

// A disc of 400 cells (above the size where a force evaluation runs on the threads) squeezed by 1 % about the
// origin, so that neighbours overlap, with random velocities of up to `speed` (so that damping and friction have
// work), every term on.
struct SqueezedDisc {
  CellMesh mesh = disc_mesh(400, 3);
  Material mat;
  Physics ph;
  std::vector<double> q, v;
  SqueezedDisc(std::uint64_t seed, double speed) {
    const std::size_t n = mesh.cells();
    mat.gamma_n = mat.gamma_t = 1000;
    mat.friction = 0.3;
    ph.laws = {"contact", "damping", "friction"};
    q = reference_state(mesh);
    for (std::size_t k = 0; k < 2 * n; ++k) q[k] *= 0.99;
    frac::Rng rng(seed);
    v.resize(3 * n);
    for (double& x : v) x = rng.uniform(-speed, speed);
  }
};

// The model's force evaluation runs every term on one team of threads (core/parallel.hpp: each thread its
// cells, its beams and the block of the contact list it filled). On 1, 2 and 3 threads it gives the same bits
// as the terms composed one by one, each a team of its own: the beams written, the contact laws in order, their
// forces added in contact order. Every term on, a squeezed disc with random velocities (so that
// damping and friction have work), 400 cells (above the size where the team runs on the threads); then again
// after some beams broke and the neighbour list was rebuilt at a moved state.
TEST(DemModel, OneTeamEvaluationEqualsTheTermsOneByOneOnAnyThreadCount) {
  const SqueezedDisc disc(11, 1.0);
  const CellMesh& mesh = disc.mesh;
  const Material& mat = disc.mat;
  const Physics& ph = disc.ph;
  const auto& q = disc.q;
  const auto& v = disc.v;
  const std::size_t n = mesh.cells();
  std::vector<double> q_moved = q;
  for (std::size_t k = 0; k < 3 * n; ++k) q_moved[k] += 0.2 * kG * v[k];  // past half the skin: a rebuild
  const std::vector<double>& moved = q_moved;
  for (const int threads : {1, 2, 3}) {
    const frac::test::ThreadCount thread_count(threads);
    Model model(mesh, mat, ph);
    // The terms one by one: a search of its own that sees the same states (it keeps what it learnt from one
    // to the next, as the model's does: the clip order of an irregular overlap changes it at round-off).
    frac::dem::ContactSearch search(mesh, model.bodies());
    for (const std::vector<double>* state : {&q, &moved}) {
      if (state == &q_moved) {
        for (std::size_t b = 0; b < model.beams().size(); b += 7) model.beams().remove(b);
      }
      std::vector<double> a(3 * n);
      model.accelerations(0, *state, v, a);
      frac::dem::Beams beams(mesh, mat);
      for (std::size_t b = 0; b < beams.size(); ++b)
        if (!model.beams().intact()[b]) beams.remove(b);
      std::vector<double> f(3 * n);
      beams.set_forces(*state, f);
      frac::dem::ContactList list;
      search.find(*state, list);
      const auto laws = frac::dem::make_contact_laws(frac::dem::contact_law_table(),
                                                     std::vector<std::string>{"contact", "damping", "friction"}, mat);
      const std::vector<double> power = frac::dem::contact_forces(laws, list, model.bodies(), *state, v);
      frac::dem::add_contact_forces(list, n, *state, f);
      const std::string where = std::to_string(threads) + " threads, " + (state == &q ? "first" : "moved") + " state";
      ASSERT_EQ(model.contacts().size(), list.size()) << where;
      ASSERT_GT(list.size(), n) << where;
      for (std::size_t k = 0; k < 3 * n; ++k) {
        ASSERT_EQ(model.forces()[k], f[k]) << where << ", coordinate " << k;
        ASSERT_EQ(a[k], f[k] * (k < 2 * n ? 1.0 / model.bodies().mass[k % n] : 1.0 / model.bodies().inertia[k % n]))
            << where << ", coordinate " << k;
      }
      ASSERT_EQ(model.contact_laws().names, (std::vector<std::string>{"contact", "damping", "friction"}));
      for (std::size_t l = 0; l < 3; ++l) EXPECT_EQ(model.law_power(l), power[l]) << where;
      EXPECT_NE(power[1], 0.0);
      EXPECT_NE(power[2], 0.0);
    }
    EXPECT_EQ(search.rebuilds(), 2);
  }
}

// The mesh's reference state with each centroid moved by up to `shift` in x and y and each cell turned by up to
// `turn`, every `far_every`-th cell by up to 3 rad instead (past the beam loops' branch-free formula).
std::vector<double> jittered_state(const CellMesh& mesh, std::uint64_t seed, double shift, double turn,
                                   std::size_t far_every) {
  const std::size_t n = mesh.cells();
  frac::Rng rng(seed);
  std::vector<double> q(3 * n);
  for (std::size_t k = 0; k < n; ++k) {
    q[k] = mesh.centroid[k].x() + shift * rng.uniform(-1, 1);
    q[n + k] = mesh.centroid[k].y() + shift * rng.uniform(-1, 1);
    q[2 * n + k] = k % far_every == 0 ? rng.uniform(-3, 3) : rng.uniform(-turn, turn);
  }
  return q;
}

// beam_response of beam b at state q, from the mesh's own geometry (not the Beams' copy of it).
frac::dem::BeamResponse exact_response(const CellMesh& mesh, const frac::dem::Beams& beams, std::span<const double> q,
                                       std::size_t b) {
  const std::size_t n = mesh.cells();
  const auto i = static_cast<std::size_t>(beams.cell_i(b)), j = static_cast<std::size_t>(beams.cell_j(b));
  const Vec2 d0 = mesh.centroid[j] - mesh.centroid[i];
  const double l0 = d0.norm();
  return frac::dem::beam_response(q[j] - q[i], q[n + j] - q[n + i], d0.x() / l0, d0.y() / l0, q[2 * n + i],
                                  q[2 * n + j], l0, beams.stiffness(b));
}

// The loop over the intact beams in beam order (F on i, −F and τ_j on j) with the exact beam law at q: the forces
// (fx, fy, torque layout), and their elastic energy into `energy`.
std::vector<double> intact_beam_forces(const CellMesh& mesh, const frac::dem::Beams& beams, std::span<const double> q,
                                       double& energy) {
  const std::size_t n = mesh.cells();
  std::vector<double> f(3 * n, 0.0);
  energy = 0;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    if (!beams.intact()[b]) continue;
    const auto i = static_cast<std::size_t>(beams.cell_i(b)), j = static_cast<std::size_t>(beams.cell_j(b));
    const auto r = exact_response(mesh, beams, q, b);
    f[i] += r.fx;
    f[n + i] += r.fy;
    f[j] -= r.fx;
    f[n + j] -= r.fy;
    f[2 * n + i] += r.torque_i;
    f[2 * n + j] += r.torque_j;
    energy += r.energy;
  }
  return f;
}

TEST(DemModel, BeamForcesAreTheSumOverIntactBeamsInBeamOrder) {
  const CellMesh mesh = rect_mesh(14, 10, 5);
  Material mat;
  frac::dem::Beams beams(mesh, mat);
  const std::size_t n = mesh.cells();
  const std::vector<double> q = jittered_state(mesh, 9, 0.01 * kG, 0.02, 7);
  for (int round = 0; round < 3; ++round) {
    if (round > 0)
      for (std::size_t b = static_cast<std::size_t>(round); b < beams.size(); b += 5) beams.remove(b);
    std::vector<double> f(3 * n, 0.0);
    beams.add_forces(q, f);
    double energy;
    const std::vector<double> expected = intact_beam_forces(mesh, beams, q, energy);
    for (std::size_t k = 0; k < 3 * n; ++k) ASSERT_EQ(f[k], expected[k]) << "round " << round << ", coordinate " << k;
  }
}

// The breaking pass over many beams (several of its blocks, some beams already broken, 1 and 2 threads) breaks
// exactly the beams the exact rule breaks, in beam order, with the exact rule's mode and energy: its vector
// bound only spares the exact evaluation where the verdict is certain.
TEST(DemModel, BreakingPassGivesTheExactRuleOfEveryBeam) {
#ifdef FRACTURE_NATIVE_BUILD
  GTEST_SKIP() << "native build: FMA contraction makes other bits than the reference's";
#endif
  const CellMesh mesh = rect_mesh(20, 14, 6);
  const Material mat;
  // Strains of neighbours up to ~±5 % (t_ε = 3 %), end rotations up to ~±0.1 rad (t_Θ = 0.07), a few far.
  const std::vector<double> q = jittered_state(mesh, 21, 0.02 * kG, 0.05, 11);
  for (const int threads : {1, 2}) {
    const frac::test::ThreadCount thread_count(threads);
    frac::dem::Beams beams(mesh, mat);
    for (std::size_t b = 3; b < beams.size(); b += 9) beams.remove(b);
    std::vector<frac::dem::BeamBreak> expected;
    for (std::size_t b = 0; b < beams.size(); ++b) {
      if (!beams.intact()[b]) continue;
      const auto r = exact_response(mesh, beams, q, b);
      const int mode = frac::dem::breaking_mode(r.strain, r.theta_i, r.theta_j, mat.t_eps, mat.t_theta);
      if (mode != 0) expected.push_back({static_cast<std::int64_t>(b), mode, r.energy});
    }
    ASSERT_GT(beams.intact_count(), 3 * 128u);
    ASSERT_GT(expected.size(), 50u);
    ASSERT_LT(expected.size(), beams.intact_count() / 2);
    const std::size_t intact = beams.intact_count();
    std::vector<frac::dem::BeamBreak> broken;
    beams.break_beams(q, mat.t_eps, mat.t_theta, broken);
    ASSERT_EQ(broken.size(), expected.size()) << threads << " threads";
    for (std::size_t k = 0; k < broken.size(); ++k) {
      EXPECT_EQ(broken[k].beam, expected[k].beam);
      EXPECT_EQ(broken[k].mode, expected[k].mode);
      EXPECT_EQ(broken[k].energy, expected[k].energy);
    }
    EXPECT_EQ(beams.intact_count(), intact - expected.size());
    // The same state again: nothing more breaks.
    beams.break_beams(q, mat.t_eps, mat.t_theta, broken);
    EXPECT_EQ(broken.size(), expected.size());
  }
}

// Beams that break stay in the active list, marked broken, until enough have gathered (Beams::kCompactEvery):
// meanwhile they give no force and no energy, count as broken, and never break again; after the compaction the
// same. One cell pulled 10 % of a cell size away breaks a few of its beams, far fewer than a compaction needs.
TEST(DemModel, BrokenBeamsWaitingForCompactionCarryNothing) {
  const CellMesh mesh = rect_mesh(20, 14, 6);
  const Material mat;
  const std::size_t n = mesh.cells();
  const std::vector<double> rest = jittered_state(mesh, 5, 0.002 * kG, 0.005, n + 1);  // nothing breaks here
  for (const int threads : {1, 2}) {
    const frac::test::ThreadCount thread_count(threads);
    frac::dem::Beams beams(mesh, mat);
    const std::size_t all = beams.intact_count();
    std::vector<frac::dem::BeamBreak> broken;
    for (std::size_t cell : {n / 3 + 4, 2 * n / 3 + 7}) {
      std::vector<double> pulled = rest;
      pulled[cell] += 0.1 * kG;
      const std::size_t had = broken.size();
      beams.break_beams(pulled, mat.t_eps, mat.t_theta, broken);
      ASSERT_GT(broken.size(), had) << threads << " threads: the pulled cell broke none of its beams";
      beams.break_beams(pulled, mat.t_eps, mat.t_theta, broken);  // the same state: nothing breaks again
      ASSERT_LT(broken.size() * frac::dem::Beams::kCompactEvery, all) << "few enough to wait in the list";
      EXPECT_EQ(beams.intact_count(), all - broken.size());
      // Forces: exactly the sum over the intact beams; energy: the intact beams' energies, to round-off.
      std::vector<double> f(3 * n, 0.0);
      beams.add_forces(rest, f);
      double energy;
      const std::vector<double> expected = intact_beam_forces(mesh, beams, rest, energy);
      for (std::size_t k = 0; k < 3 * n; ++k) ASSERT_EQ(f[k], expected[k]) << threads << " threads, coordinate " << k;
      EXPECT_NEAR(beams.energy(rest), energy, 1e-12 * energy) << threads << " threads";
    }
    // Enough broken beams for a compaction (every 7th cell pulled): then no broken beam waits in the list.
    std::vector<double> pulled = rest;
    for (std::size_t cell = 3; cell < n; cell += 7) pulled[cell] += 0.1 * kG;
    beams.break_beams(pulled, mat.t_eps, mat.t_theta, broken);
    ASSERT_GT(broken.size() * frac::dem::Beams::kCompactEvery, all);
    const std::size_t had = broken.size();
    beams.break_beams(pulled, mat.t_eps, mat.t_theta, broken);
    EXPECT_EQ(broken.size(), had) << "a beam broken before broke again";
    EXPECT_EQ(beams.intact_count(), all - broken.size());
    double energy;
    intact_beam_forces(mesh, beams, rest, energy);
    EXPECT_NEAR(beams.energy(rest), energy, 1e-12 * energy) << threads << " threads";
  }
}

// Each beam's constants and strain stay its own wherever it is kept: intact, broken and waiting in the active
// table, or moved out at a compaction (Beams keeps one table in two parts). Checked against the mesh itself on
// every beam, after single removals and a compaction; the strain of a broken beam is still computed (frames).
TEST(DemModel, EveryBeamKeepsItsConstantsAndStrainWhenBroken) {
  const CellMesh mesh = rect_mesh(20, 14, 6);
  const Material mat;
  const std::size_t n = mesh.cells();
  frac::dem::Beams beams(mesh, mat);
  for (std::size_t b = 5; b < beams.size(); b += 17) beams.remove(b);
  std::vector<double> pulled = jittered_state(mesh, 5, 0.002 * kG, 0.005, n + 1);
  for (std::size_t cell = 3; cell < n; cell += 7) pulled[cell] += 0.1 * kG;
  std::vector<frac::dem::BeamBreak> broken;
  beams.break_beams(pulled, mat.t_eps, mat.t_theta, broken);
  ASSERT_GT(broken.size() * frac::dem::Beams::kCompactEvery, beams.size()) << "enough for a compaction";
  const std::vector<double> q = jittered_state(mesh, 9, 0.01 * kG, 0.02, 7);
  std::vector<double> strain(beams.size());
  beams.strains(q, strain);
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const auto i = static_cast<std::size_t>(mesh.beam[b][0]), j = static_cast<std::size_t>(mesh.beam[b][1]);
    ASSERT_EQ(beams.cell_i(b), mesh.beam[b][0]) << "beam " << b;
    ASSERT_EQ(beams.cell_j(b), mesh.beam[b][1]) << "beam " << b;
    const Vec2 d0 = mesh.centroid[j] - mesh.centroid[i];
    const double l0 = d0.norm();
    EXPECT_EQ(beams.rest_length(b), l0) << "beam " << b;
    const auto k =
        frac::dem::beam_stiffness(l0, mesh.beam_section[b], mat.thickness, mat.beam_modulus, mat.shear_ratio);
    EXPECT_EQ(beams.stiffness(b).alpha, k.alpha) << "beam " << b;
    EXPECT_EQ(beams.stiffness(b).delta, k.delta) << "beam " << b;
    const auto r = frac::dem::beam_response(q[j] - q[i], q[n + j] - q[n + i], d0.x() / l0, d0.y() / l0, q[2 * n + i],
                                            q[2 * n + j], l0, k);
    // (The strains of 1e-2 from the vector formula or the exact one: round-off apart at most.)
    EXPECT_NEAR(strain[b], r.strain, 1e-15) << "beam " << b << (beams.intact()[b] ? "" : " (broken)");
  }
}

}  // namespace
