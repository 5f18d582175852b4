// The driven seed (crack.drive_speed, crack.drive_length; lib/rubber/crack_drive.hpp): off, nothing is
// scheduled and a run is unchanged; on, the knife removes exactly the bonds crossing the crack line between
// the seed tip and seed + drive_length, each at t = λx (x − x_min − seed_length) / drive_speed, and books the
// potential energy the cuts change, so that total − drive energy is conserved.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/scene.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"

namespace {

using namespace frac;
using namespace frac::rubber;

mesh::NodeMesh strip(std::int64_t nx, std::int64_t ny) {
  mesh::TriangularLatticeOptions o;
  o.nx = nx;
  o.ny = ny;
  o.spacing = 1e-3;
  return mesh::make_triangular_lattice(o);
}

RubberSetup setup_for(const std::string& extra, const mesh::NodeMesh& m) {
  const std::string text =
      "[loading]\nkind = stretch\nstretch_x = 1.2\nstretch_y = 3\n[law]\ncutoff_length = 3.45e-3\n"
      "[boundary]\nclamp_columns = 2\n[stop]\nt_max = 5e-4\n[output]\nobserve_every = 5\n" +
      extra;
  Scene s = Scene::parse(text, "drive.ini");
  const RubberScene sc = read_rubber_scene(s, m);
  s.check_all_used();
  return prepare_rubber(sc, m);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RubberDrive, OffSchedulesNothingAndKeysGoTogether) {
  const auto m = strip(40, 12);
  const RubberSetup off = setup_for("[crack]\nseed_length = 0.01\n", m);
  EXPECT_EQ(off.scene.drive_speed, 0);
  RubberSystem sys = build_rubber(m, off, 1, 1);
  EXPECT_EQ(sys.drive, nullptr);
  EXPECT_THROW(setup_for("[crack]\nseed_length = 0.01\ndrive_speed = 20\n", m), UsageError);
  EXPECT_THROW(setup_for("[crack]\nseed_length = 0.01\ndrive_length = 0.01\n", m), UsageError);
}

// A knife so slow that it reaches its first bond long after the run: the run is the run without it, bit
// for bit (energies, bonds past u_c, tip), and it cut nothing.
TEST(RubberDrive, AKnifeThatCutsNothingChangesNothing) {
  const auto m = strip(40, 12);
  const std::string common = "[crack]\nseed_length = 0.01\n";
  const RubberSetup off = setup_for(common, m);
  const RubberSetup idle = setup_for(common + "drive_speed = 1e-6\ndrive_length = 0.01\n", m);
  RubberSystem a = build_rubber(m, off, 1, 1), b = build_rubber(m, idle, 1, 1);
  ASSERT_NE(b.drive, nullptr);
  EXPECT_GT(b.drive->scheduled(), 0u);
  EXPECT_GT(b.drive->cut_time(0), 1.0);
  Progress quiet("test", true);
  const RubberSummary sa = run_rubber(a, off, m, quiet), sb = run_rubber(b, idle, m, quiet);
  EXPECT_EQ(sb.driven, 0u);
  EXPECT_EQ(sb.drive_energy, 0);
  EXPECT_EQ(sa.steps, sb.steps);
  EXPECT_TRUE(same_bits(sa.energy_end, sb.energy_end));
  EXPECT_EQ(sa.events, sb.events);
  EXPECT_TRUE(same_bits(sa.tip.reference_x, sb.tip.reference_x));
}

TEST(RubberDrive, TheKnifeCutsTheCrossingBondsOnSchedule) {
  const auto m = strip(60, 16);
  const double seed = 0.01, speed = 24, length = 0.02, lx = 1.2;
  const RubberSetup su = setup_for("[crack]\nseed_length = 0.01\ndrive_speed = 24\ndrive_length = 0.02\n", m);
  RubberSystem sys = build_rubber(m, su, 1, 1);
  ASSERT_NE(sys.drive, nullptr);
  const CrackPath& path = *sys.path;
  const CrackDrive& drive = *sys.drive;
  // The schedule: every crossing bond in [seed, seed + length) beyond x_min, in order, at its time.
  std::size_t expected = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const double x = path.crossing(k) - path.x_min();
    if (x < seed || x >= seed + length) continue;
    ASSERT_LT(expected, drive.scheduled());
    EXPECT_EQ(drive.bond(expected), path.bond(k));
    EXPECT_NEAR(drive.cut_time(expected), lx * (x - seed) / speed, 1e-15);
    ++expected;
  }
  EXPECT_EQ(drive.scheduled(), expected);
  EXPECT_GT(expected, 30u);  // two crossing bonds per spacing
  EXPECT_NEAR(drive.end_time(), lx * length / speed, 1e-15);

  // Half way through the drive (t_max = 5e-4 s of 1e-3 s): the bonds whose time has come are gone, the
  // others (and every crossing bond beyond the drive) still there.
  Progress quiet("test", true);
  const RubberSummary s = run_rubber(sys, su, m, quiet);
  std::size_t removed = 0;
  for (std::size_t k = 0; k < drive.scheduled(); ++k) {
    const auto status = sys.model->status(drive.bond(k));
    if (drive.cut_time(k) <= s.time - 0.5 * su.dt) {
      EXPECT_EQ(status, kRemoved) << "bond " << k << " due at " << drive.cut_time(k);
      ++removed;
    } else if (drive.cut_time(k) > s.time + 0.5 * su.dt) {
      EXPECT_EQ(status, kIntact) << "bond " << k << " due at " << drive.cut_time(k);
    }
  }
  EXPECT_GT(removed, 10u);
  EXPECT_LT(removed, drive.scheduled());
  EXPECT_EQ(s.driven, removed);
  for (std::size_t k = 0; k < path.size(); ++k)
    if (path.crossing(k) - path.x_min() >= seed + length) {
      EXPECT_EQ(sys.model->status(path.bond(k)), kIntact);
    }
  // The tip is at least where the knife is; the energy balance holds once the knife's work is booked (to
  // 0.02-0.15% at safety 0.5-0.125 here, no trend with dt: bonds fail through the cut-off behind the knife).
  EXPECT_GE(s.tip.reference_x - path.x_min(), seed + s.time * speed / lx - 1e-3);
  EXPECT_NE(s.drive_energy, 0);
  EXPECT_NEAR(s.energy_end - s.drive_energy, s.energy_start, 5e-3 * std::abs(s.energy_start));
}

}  // namespace
