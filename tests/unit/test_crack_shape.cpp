// The crack shape of a rubber run's frame (analysis/crack_shape) on synthetic frames of known shape, and the
// Mach angle of the Mooney-Rivlin sheet (analysis/mooney_rivlin_waves).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/crack_shape.hpp"
#include "analysis/mooney_rivlin_waves.hpp"
#include "core/error.hpp"
#include "mesh/triangular_lattice.hpp"

using namespace frac;
using namespace frac::analysis;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 200 x 40 strip pre-stretched to (1.2, 3), Δ = 1: the crack line broken up to reference x = tip, and
// behind a front at `angle` to the line through the tip's lab position every free node moved 3Δ away from
// the line (bonds crossing the front not touched: only positions count for the front).
struct Synthetic {
  mesh::NodeMesh mesh;
  io::BodyFrame frame;
};
Synthetic wedge(double tip, double angle_deg, std::size_t clamp_rows) {
  Synthetic s;
  s.mesh = mesh::make_triangular_lattice({200, 40, 1.0, "x", 0.0});
  const double lx = 1.2, ly = 3.0, y0 = s.mesh.notch_y;
  s.frame.time = 1e-3;
  s.frame.intact.assign(s.mesh.bonds(), 1);
  s.frame.strain.assign(s.mesh.bonds(), 0.0);
  for (std::size_t b = 0; b < s.mesh.bonds(); ++b) {
    const auto& p = s.mesh.position[static_cast<std::size_t>(s.mesh.bond[b][0])];
    const auto& q = s.mesh.position[static_cast<std::size_t>(s.mesh.bond[b][1])];
    if ((p.y() < y0) != (q.y() < y0) && 0.5 * (p.x() + q.x()) < tip) s.frame.intact[b] = 0;
  }
  const double tip_lab = lx * tip, slope = 1.0 / std::tan(angle_deg * kDeg);
  const std::size_t nx = 200, ny = 40;
  for (std::size_t i = 0; i < s.mesh.nodes(); ++i) {
    const auto& r = s.mesh.position[i];
    double x = lx * r.x(), y = ly * r.y();
    const std::size_t row = i / nx;
    const bool clamped = row < clamp_rows || row + clamp_rows >= ny;
    const double h = ly * std::abs(r.y() - y0);
    if (!clamped && x < tip_lab - slope * h) y += r.y() > y0 ? 3.0 : -3.0;
    s.frame.position.insert(s.frame.position.end(), {x, y});
  }
  return s;
}

}  // namespace

TEST(CrackShape, WedgeOfKnownAngleWithTheTipAtItsApex) {
  for (double angle : {45.0, 60.0, 75.0, 90.0}) {
    const Synthetic s = wedge(120.0, angle, 2);
    const CrackShape c = measure_crack_shape(s.mesh, s.frame, 1.2, 3.0, 2);
    ASSERT_TRUE(c.tip_found);
    EXPECT_NEAR(c.tip_reference_x, 119.75, 0.5);
    EXPECT_NEAR(c.tip_x, 1.2 * c.tip_reference_x, 0.7);
    // The front is read node by node (Δ apart along a row): its angle to within a degree or two.
    EXPECT_NEAR(c.front_angle, angle, 2.0) << angle;
    EXPECT_NEAR(c.front_angle_upper, angle, 2.5) << angle;
    EXPECT_NEAR(c.front_angle_lower, angle, 2.5) << angle;
    EXPECT_LT(std::abs(c.front_lag), 1.5) << angle;
    EXPECT_EQ(c.front_rows, 18u);  // the rows from the line halfway to the grips: 9 on each side
    EXPECT_EQ(c.broken_bulk, 0u);
    EXPECT_NEAR(static_cast<double>(c.grip_bonds), 2 * 2 * 120, 4);  // behind the tip: two a node, both grips
    EXPECT_EQ(c.grip_bonds_broken, 0u);
    EXPECT_EQ(c.free_nodes, 36u * 200);
    EXPECT_EQ(c.nodes_past_grips, 0u);
  }
}

TEST(CrackShape, GripsAndDebris) {
  Synthetic s = wedge(120.0, 60.0, 2);
  // Two free nodes thrown far past the grips (one only a little: it counts as folded over its grip), the bonds
  // of a node behind the tip to the bottom clamp broken, and of one ahead of it (not counted).
  s.frame.position[2 * (37 * 200 + 10) + 1] = 200.0;
  s.frame.position[2 * (3 * 200 + 10) + 1] = -50.0;
  s.frame.position[2 * (4 * 200 + 10) + 1] = -5.0;
  std::size_t cut = 0;
  for (std::size_t b = 0; b < s.mesh.bonds(); ++b)
    if ((s.mesh.bond[b][1] == 2 * 200 + 50 || s.mesh.bond[b][1] == 2 * 200 + 150) && s.mesh.bond[b][0] < 2 * 200) {
      s.frame.intact[b] = 0;
      ++cut;
    }
  const CrackShape c = measure_crack_shape(s.mesh, s.frame, 1.2, 3.0, 2);
  EXPECT_EQ(c.nodes_past_grips, 2u);
  EXPECT_EQ(cut, 4u);
  EXPECT_EQ(c.grip_bonds_broken, 2u);
  EXPECT_EQ(c.broken_bulk, 4u);
}

TEST(CrackShape, NoCrackAndBadMeshes) {
  Synthetic s = wedge(-10.0, 60.0, 2);  // nothing broken, nothing moved
  const CrackShape c = measure_crack_shape(s.mesh, s.frame, 1.2, 3.0, 2);
  EXPECT_FALSE(c.tip_found);
  EXPECT_EQ(c.front_rows, 0u);
  EXPECT_TRUE(std::isnan(c.front_angle));
  EXPECT_TRUE(std::isnan(c.front_lag));
  const mesh::NodeMesh turned = mesh::make_triangular_lattice({20, 20, 1.0, "y", 0.0});
  EXPECT_THROW(measure_crack_shape(turned, s.frame, 1.2, 3.0, 2), InputError);
  EXPECT_THROW(measure_crack_shape(s.mesh, io::BodyFrame{}, 1.2, 3.0, 2), InputError);
}

TEST(MachAngle, IsotropicSheetGivesAsinOfTheSpeedRatio) {
  // b = 0: c_T = c_L = λ√a in every direction of an equibiaxial stretch, so sin α = c/v.
  const MooneyRivlin m{1600, 0.0, 1.0};
  const double c = 1.5 * 40.0;
  for (double v : {61.0, 90.0, 200.0}) EXPECT_NEAR(mach_angle(m, {1.5, 1.5}, v, true), std::asin(c / v), 1e-12) << v;
  EXPECT_TRUE(std::isnan(mach_angle(m, {1.5, 1.5}, 59.0, true)));
}

TEST(MachAngle, StretchedSheetSatisfiesTheSteadyFrontCondition) {
  // (1.2, 3), b = 1.5: v sin α = c(n), n = (sin α, cos α); faster waves across the crack tilt the front up.
  const MooneyRivlin m{1600, 1.5, 1.0};
  const Stretch s{1.2, 3.0};
  const double v = 148.7;
  for (bool longitudinal : {true, false}) {
    const double alpha = mach_angle(m, s, v, longitudinal);
    const MrWaveSpeeds c = mooney_rivlin_speeds(m, s, std::numbers::pi / 2 - alpha);
    EXPECT_NEAR(v * std::sin(alpha), longitudinal ? c.longitudinal : c.shear, 1e-9);
    const double along_x =
        longitudinal ? mooney_rivlin_speeds(m, s, 0).longitudinal : mooney_rivlin_speeds(m, s, 0).shear;
    EXPECT_GT(alpha, std::asin(along_x / v));
  }
  EXPECT_NEAR(mach_angle(m, s, v, true) / kDeg, 60.8, 0.1);
  EXPECT_NEAR(mach_angle(m, s, v, false) / kDeg, 22.2, 0.1);
}
