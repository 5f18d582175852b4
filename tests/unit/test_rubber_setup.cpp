// rubber-run's scene and set-up: defaults from the physics note in units of the mesh spacing, the
// far-field warnings (rubber-lattice-validation.md §D.1), the time-step bound, the initial state (seed
// crack, clamps, pulse), the crack tip, and a short run of the driver.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/scene.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/run.hpp"
#include "rubber/run_file.hpp"
#include "rubber/setup.hpp"

namespace {

using namespace frac;
using namespace frac::rubber;

mesh::NodeMesh strip(std::int64_t nx, std::int64_t ny, const char* rows = "x", double notch = 0) {
  mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = 1e-3;
  o.rows_along = rows;
  o.notch = notch;
  return mesh::make_triangular_lattice(o);
}

RubberSetup setup_for(const std::string& text, const mesh::NodeMesh& m) {
  Scene s = Scene::parse(text, "test.ini");
  const RubberScene sc = read_rubber_scene(s, m);
  s.check_all_used();
  return prepare_rubber(sc, m);
}

const char* kStretch = "[loading]\nkind = stretch\nstretch_x = 1.2\nstretch_y = 3\n";

TEST(RubberSetup, DefaultsComeFromTheNoteInUnitsOfTheSpacing) {
  const auto m = strip(20, 10);
  Scene s = Scene::parse("[loading]\nstretch_x = 1.2\n", "t.ini");
  const RubberScene sc = read_rubber_scene(s, m);
  EXPECT_DOUBLE_EQ(sc.short_width, 0.1e-3);
  EXPECT_DOUBLE_EQ(sc.cutoff_width, 0.05e-3);
  EXPECT_DOUBLE_EQ(sc.cutoff_length, 3.5e-3);
  EXPECT_DOUBLE_EQ(sc.b, 1.5);
  EXPECT_EQ(sc.clamp_rows, 2);  // stretch: top and bottom 2 rows
  EXPECT_EQ(sc.integrator, dynamics::IntegratorKind::verlet);
  EXPECT_NEAR(sc.t_max, 100 * 1e-3 / 40, 1e-15);  // 100 time units Δ/√a
  // Every key read is recorded; an unknown one is refused by name.
  bool found = false;
  for (const auto& [k, v] : s.resolved()) found = found || k == "law.cutoff_length";
  EXPECT_TRUE(found);
  Scene bad = Scene::parse("[law]\ncutof_length = 3e-3\n", "bad.ini");
  read_rubber_scene(bad, m);
  EXPECT_THROW(bad.check_all_used(), UsageError);
}

TEST(RubberSetup, RefusesBadValuesNamingTheKey) {
  const auto m = strip(20, 10);
  for (const char* text : {"[law]\ncutoff_length = 1e-3\n", "[boundary]\nclamp_rows = 5\n", "[pulse]\nposition = 2\n",
                           "[integrator]\nsafety = 2\n", "[boundary]\nperiodic = y\nclamp_rows = 2\n"}) {
    Scene s = Scene::parse(text, "t.ini");
    EXPECT_THROW(read_rubber_scene(s, m), UsageError) << text;
  }
}

TEST(RubberSetup, FarFieldWarningsNameTheNumbers) {
  const auto m = strip(20, 10);
  // u_0 = 2.666Δ at (1.2, 3); Fermi width 0.05Δ: 15.7 widths is quiet, 6.7 widths warns.
  EXPECT_TRUE(setup_for(std::string(kStretch) + "[law]\ncutoff_length = 3.45e-3\n", m).warnings.empty());
  const RubberSetup near = setup_for(std::string(kStretch) + "[law]\ncutoff_length = 3.0e-3\n", m);
  ASSERT_EQ(near.warnings.size(), 1u);
  EXPECT_NE(near.warnings[0].find("6.67 cut-off widths"), std::string::npos) << near.warnings[0];
  EXPECT_NE(near.warnings[0].find("u_0 = 0.0026665 m"), std::string::npos) << near.warnings[0];
  EXPECT_NE(near.warnings[0].find("stiffens the far field"), std::string::npos);
  EXPECT_GT(near.lattice_x.transverse, 2 * near.mr_x.transverse);  // what the warning is about
  // The smoothstep cut-off is exactly 1 below u_c − L: no warning however close, until it reaches u_0.
  const RubberSetup soft = setup_for(
      std::string(kStretch) + "[law]\ncutoff = smoothstep\ncutoff_length = 2.72e-3\ncutoff_width = 5e-5\n", m);
  EXPECT_TRUE(soft.warnings.empty()) << soft.warnings[0];
  EXPECT_NEAR(soft.lattice_x.transverse, soft.mr_x.transverse, 0.01 * soft.mr_x.transverse);
  const RubberSetup reach = setup_for(
      std::string(kStretch) + "[law]\ncutoff = smoothstep\ncutoff_length = 2.70e-3\ncutoff_width = 5e-5\n", m);
  ASSERT_EQ(reach.warnings.size(), 1u);
  EXPECT_NE(reach.warnings[0].find("reaches the far-field bonds"), std::string::npos) << reach.warnings[0];
  // A bond family in the short-bond branch (λx = 1, rows along x), and the way out.
  const RubberSetup shortb = setup_for("[loading]\nstretch_x = 1\nstretch_y = 3\n", m);
  ASSERT_FALSE(shortb.warnings.empty());
  EXPECT_NE(shortb.warnings[0].find("not Mooney-Rivlin"), std::string::npos);
  EXPECT_NE(shortb.warnings[0].find("--rows-along y"), std::string::npos);
  // Turned: bonds at 30 and 150 degrees are 1.73Δ, those along y 3Δ (u_c 4Δ keeps 20 widths above).
  const RubberSetup turned =
      setup_for("[loading]\nstretch_x = 1\nstretch_y = 3\n[law]\ncutoff_length = 4e-3\n", strip(20, 10, "y"));
  EXPECT_TRUE(turned.warnings.empty()) << turned.warnings[0];
}

// Irreversible breaking mid-cut-off with a three-body term: a warning naming the weight h left at the cut.
TEST(RubberSetup, WarnsWhenIrreversibleBreakingCutsBondsMidCutoff) {
  const auto m = strip(20, 10);
  const std::string scene = std::string(kStretch) + "[law]\ncutoff_length = 3.45e-3\n[physics]\nirreversible = on\n";
  // The scene's 10 Fermi widths leave h = 4.5e-5: quiet.
  EXPECT_TRUE(setup_for(scene, m).warnings.empty()) << setup_for(scene, m).warnings[0];
  // 0.2 widths leave h = 1/(1 + e^0.2) = 0.45.
  const RubberSetup mid = setup_for(scene + "[breaking]\nextra_widths = 0.2\n", m);
  ASSERT_EQ(mid.warnings.size(), 1u);
  EXPECT_NE(mid.warnings[0].find("breaking.extra_widths = 0.2"), std::string::npos) << mid.warnings[0];
  EXPECT_NE(mid.warnings[0].find("h is still 0.45"), std::string::npos) << mid.warnings[0];
  // Not without the three-body term (b = 0), nor for reversible bonds, nor past a compact cut-off (h = 0).
  EXPECT_TRUE(setup_for(scene + "[material]\nb = 0\n[breaking]\nextra_widths = 0.2\n", m).warnings.empty());
  EXPECT_TRUE(setup_for(std::string(kStretch) + "[law]\ncutoff_length = 3.45e-3\n[breaking]\nextra_widths = 0.2\n", m)
                  .warnings.empty());
  EXPECT_TRUE(setup_for(std::string(kStretch) +
                            "[law]\ncutoff = smoothstep\ncutoff_length = 2.786e-3\ncutoff_width = 1e-4\n"
                            "[physics]\nirreversible = on\n[breaking]\nextra_widths = 0.2\n",
                        m)
                  .warnings.empty());
}

TEST(RubberSetup, TimeStepIsBoundedByTheStiffestStateAndRefusedAbove) {
  const auto m = strip(20, 10);
  const RubberSetup su = setup_for(kStretch, m);
  // ω_max in units of √a/Δ = 40 / 1e-3: the far field 13.8 (the note), the cut-off about 10 times more.
  EXPECT_NEAR(su.omega_far * 1e-3 / 40, 13.8, 0.3);
  EXPECT_GT(su.omega_cutoff, 5 * su.omega_far);
  EXPECT_DOUBLE_EQ(su.dt_bound, 2 / su.omega_max);
  EXPECT_DOUBLE_EQ(su.dt, 0.5 * su.dt_bound);
  try {
    setup_for(std::string(kStretch) + "[integrator]\ndt = 1e-5\n", m);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("above the stability bound"), std::string::npos);
  }
  EXPECT_NO_THROW(setup_for(std::string(kStretch) + "[integrator]\ndt = 1e-5\nallow_unstable = on\n", m));
}

TEST(RubberSetup, InitialStateSeedClampsAndPulse) {
  const auto m = strip(60, 20);
  const RubberSetup su = setup_for(std::string(kStretch) + "[crack]\nseed_length = 0.0101\n", m);
  RubberSystem sys = build_rubber(m, su, 1, 1);
  // 10 spacings of crack line: about 20 crossing bonds cut, the tip near x = 10Δ.
  EXPECT_GE(sys.seeded, 19u);
  EXPECT_LE(sys.seeded, 21u);
  const CrackPath::Tip tip = sys.path->tip(*sys.model, sys.q0);
  ASSERT_TRUE(tip.found);
  EXPECT_NEAR(tip.reference_x, 0.0101, 0.6e-3);
  EXPECT_NEAR(tip.lab_x, 1.2 * tip.reference_x, 0.6e-3);
  // Top 2 and bottom 2 rows clamped: 4 × 60 nodes, x and y each.
  EXPECT_EQ(sys.model->clamped_nodes().size(), 240u);
  EXPECT_EQ(sys.model->prescribed().size(), 480u);

  const RubberSetup wave = setup_for(
      "[loading]\nkind = wave\nstretch_x = 1.2\nstretch_y = 3\n[boundary]\nperiodic = y\nclamp_columns = 2\n"
      "[pulse]\nkind = shear\namplitude = 1e-5\nwidth = 3e-3\n",
      m);
  RubberSystem w = build_rubber(m, wave, 1, 1);
  const std::size_t n = m.nodes();
  // The shear pulse displaces y only, most in the middle column.
  double max_dy = 0, max_dx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    max_dx = std::max(max_dx, std::abs(w.q0[i] - 1.2 * m.position[i].x()));
    max_dy = std::max(max_dy, std::abs(w.q0[n + i] - 3 * m.position[i].y()));
  }
  EXPECT_LT(max_dx, 1e-15);
  EXPECT_NEAR(max_dy, 1e-5, 2e-7);
}

// loading.ramp_time: the sheet starts at λy = ramp_from_y moving at the homogeneous stretch rate, and the
// clamped rows keep that rate until ramp_time, then stay at stretch_y.
TEST(RubberSetup, RampMovesTheClampedRowsToTheStretch) {
  const auto m = strip(30, 16);
  const RubberSetup su = setup_for(std::string(kStretch) + "ramp_time = 1e-4\nramp_from_y = 2\n", m);
  RubberSystem sys = build_rubber(m, su, 1, 1);
  const std::size_t n = m.nodes();
  const double rate = (3.0 - 2.0) / 1e-4;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(sys.q0[n + i], 2 * m.position[i].y(), 1e-15);
    EXPECT_NEAR(sys.v0[n + i], rate * m.position[i].y(), 1e-12);
  }
  for (const auto& [t, stretch, moving] : {std::tuple{0.5e-4, 2.5, true}, std::tuple{2e-4, 3.0, false}}) {
    std::vector<double> q = sys.q0, v = sys.v0, a(2 * n, 0.0);
    sys.model->prescribe(t, q, v, a);
    for (std::size_t i : sys.model->clamped_nodes()) {
      EXPECT_NEAR(q[n + i], stretch * m.position[i].y(), 1e-15);
      EXPECT_NEAR(v[n + i], moving ? rate * m.position[i].y() : 0.0, 1e-12);
      EXPECT_NEAR(q[i], 1.2 * m.position[i].x(), 1e-15);
    }
  }
  EXPECT_THROW(setup_for(std::string(kStretch) + "ramp_time = 1e-4\n[boundary]\nclamp_rows = 0\n", m), UsageError);
}

// A run of the stretch scene plus `extra` on a 40 × 16 strip with clamped columns, observed every 5 steps.
std::pair<RubberSetup, RubberSummary> short_run(const std::string& extra) {
  const auto m = strip(40, 16);
  RubberSetup su =
      setup_for(std::string(kStretch) + extra + "[boundary]\nclamp_columns = 2\n[output]\nobserve_every = 5\n", m);
  RubberSystem sys = build_rubber(m, su, 1, 1);
  Progress quiet("test", true);
  RubberSummary s = run_rubber(sys, su, m, quiet);
  return {std::move(su), std::move(s)};
}

TEST(RubberSetup, ShortRunConservesEnergyAndKeepsTheTip) {
  const auto [su, s] = short_run("[crack]\nseed_length = 0.008\n[stop]\nt_max = 2.5e-5\n");
  EXPECT_EQ(s.stop_reason, "stop.t_max reached");
  EXPECT_NEAR(s.time, 2.5e-5, 0.51 * su.dt);
  EXPECT_NEAR(s.energy_end, s.energy_start, 1e-4 * std::abs(s.energy_start));
  EXPECT_TRUE(s.tip.found);
  EXPECT_GE(s.tip.reference_x, s.tip_start.reference_x);
  EXPECT_GT(s.ns_per_node_step(), 0);
}

// While loading.ramp_time moves the clamped rows they work on the sheet; the undamped run conserves its energy
// only from then on, and the energy check starts there (it warned of a too-large time step before).
TEST(RubberSetup, EnergyCheckStartsWhenTheClampedRowsStop) {
  const auto [su, s] = short_run("ramp_time = 1e-5\nramp_from_y = 2.9\n[stop]\nt_max = 3e-5\n");
  ASSERT_TRUE(s.energy_conserved_set);
  EXPECT_GE(s.energy_conserved_time, 1e-5);
  EXPECT_LT(s.energy_conserved_time, 1e-5 + 5.01 * su.dt);  // the first observation from the ramp's end on
  // While they raise λy from 2.9 to 3 (and when they stop: their rows' kinetic energy goes), the clamped rows
  // change the sheet's energy by more than the check's 1 %.
  EXPECT_GT(std::abs(s.energy_end - s.energy_start), 0.01 * std::abs(s.energy_start))
      << s.energy_start << " -> " << s.energy_end;
  EXPECT_NEAR(s.energy_end, s.energy_conserved, 1e-4 * std::abs(s.energy_conserved));
  EXPECT_FALSE(energy_warning(s, su.scene).has_value());
  // The same summary with the energy changed by 2 % after the grips stopped: the check speaks.
  RubberSummary drifted = s;
  drifted.energy_end = 1.02 * s.energy_conserved;
  const auto warning = energy_warning(drifted, su.scene);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find("since the clamped rows stopped"), std::string::npos) << *warning;
}

}  // namespace
