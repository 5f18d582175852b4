// One beam of the polygon DEM (lib/dem/beam.hpp; physics/polygon-dem.md §4 and §5, validation E4-E6):
// Timoshenko stiffnesses, the co-rotational response against the note's formulas, the linear
// small-displacement form, cantilever and carry-over, rigid rotations, the energy gradient, and the
// breaking rule.
//
// Tolerances, in general:
// - Closed forms of the stiffnesses: a handful of roundings each, 1e-13 relative.
// - The co-rotational formulas re-implemented here: the library and this file compute the axis rotation
//   differently (atan2 of cross/dot against a difference of atan2), each accurate to ~1e-16 absolute in
//   angle; the stretch l − l0 loses log10(1/ε) digits to cancellation, so at ε ≥ 1e-3 it is good to
//   ~1e-13 relative. 1e-12 of the force scale.
// - The linear (small-displacement) form of §4 differs from the co-rotational law at second order, i.e.
//   by a relative O(displacement/l0). At displacements of 1e-10·l0 that is ~1e-10, inside the 1e-9 of
//   the acceptance list; round-off stays below that only with the beam along x (then l = dx exactly
//   and dx − l0 is exact by Sterbenz, so no stretch is invented by rounding), which is why those cases
//   are axis-aligned. Objectivity (rotations) is tested separately.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "dem/beam.hpp"

namespace {

using frac::dem::beam_response;
using frac::dem::beam_stiffness;
using frac::dem::BeamResponse;
using frac::dem::BeamStiffness;
using frac::dem::breaking_mode;
using frac::dem::wrap_angle;

constexpr double kPi = std::numbers::pi;
// Table 1 in SI, h = 1 cm; a typical VRL beam (g ≈ 1.07 cm).
constexpr double kE = 5e8, kH = 0.01, kShearRatio = 2.0;
constexpr double kL0 = 0.0107, kS = 0.0061;

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

TEST(DemBeam, StiffnessClosedForms) {
  // For several shapes and shear ratios: α = E S h/l0, and the Timoshenko forms of β and δ with
  // I = h S³/12, G = E/shear_ratio, Φ = 12 E I/(G S h l0²).
  for (double sr : {2.0, 2.6}) {
    for (double s_over_l : {0.05, 0.3, 1.0 / std::sqrt(3.0), 1.2}) {
      const double l0 = kL0, S = s_over_l * l0;
      const BeamStiffness k = beam_stiffness(l0, S, kH, kE, sr);
      const double EI = kE * kH * S * S * S / 12, GA = kE / sr * S * kH;
      const double phi = 12 * EI / (GA * l0 * l0);
      EXPECT_LT(rel(k.alpha, kE * S * kH / l0), 1e-13);
      EXPECT_LT(rel(k.beta, 12 * EI / (l0 * l0 * l0 * (1 + phi))), 1e-13);
      EXPECT_LT(rel(k.delta * l0 * l0, (4 + phi) * EI / (l0 * (1 + phi))), 1e-13);
      if (sr == 2.0) {
        // The note's G = E/2 forms: β = E h S³/(l0 (l0² + 2 S²)), b/c = S²/(6 l0²), Φ = 2 S²/l0².
        EXPECT_LT(rel(k.beta, kE * kH * S * S * S / (l0 * (l0 * l0 + 2 * S * S))), 1e-13);
        EXPECT_LT(rel(k.delta, k.beta * (S * S / (6 * l0 * l0) + 1.0 / 3.0)), 1e-13);
        EXPECT_LT(rel(phi, 2 * S * S / (l0 * l0)), 1e-13);
      }
    }
  }
}

TEST(DemBeam, RegularHexagonValues) {
  // Validation E6: S = l0/√3 gives β/α = 1/5, δ = 7√3/270·E·h, Φ = 2/3.
  const double S = kL0 / std::sqrt(3.0);
  const BeamStiffness k = beam_stiffness(kL0, S, kH, kE, kShearRatio);
  EXPECT_LT(rel(k.alpha, kE * kH / std::sqrt(3.0)), 1e-13);
  EXPECT_LT(rel(k.beta / k.alpha, 0.2), 1e-13);
  EXPECT_LT(rel(k.delta, 7 * std::sqrt(3.0) / 270 * kE * kH), 1e-13);
}

TEST(DemBeam, WrapAngle) {
  EXPECT_EQ(wrap_angle(0.0), 0.0);
  EXPECT_EQ(wrap_angle(kPi), kPi);
  EXPECT_EQ(wrap_angle(-kPi), kPi);  // (−π, π]: −π maps to π
  frac::Rng rng(11);
  for (int k = 0; k < 10000; ++k) {
    const double x = (rng.uniform() - 0.5) * 200;
    const double w = wrap_angle(x);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    const double turns = (x - w) / (2 * kPi);
    EXPECT_NEAR(turns, std::round(turns), 1e-13) << x;
  }
  for (double x : {3 * kPi, -3 * kPi, 5 * kPi + 1e-12, 1e6}) {
    const double w = wrap_angle(x);
    EXPECT_GT(w, -kPi) << x;
    EXPECT_LE(w, kPi) << x;
  }
}

// The co-rotational law exactly as the note writes it (§4), coded independently of the library.
struct Expected {
  double fx, fy, mi, mj, energy, strain, ti, tj;
};
double my_wrap(double x) {
  double w = std::fmod(x + kPi, 2 * kPi);
  if (w <= 0) w += 2 * kPi;
  return w - kPi;  // (−π, π]
}
Expected note_law(double dx, double dy, double psi0, double phi_i, double phi_j, double l0, const BeamStiffness& k) {
  const double l = std::hypot(dx, dy);
  const double ex = dx / l, ey = dy / l, tx = -ey, ty = ex;
  const double dpsi = my_wrap(std::atan2(dy, dx) - psi0);
  const double ti = my_wrap(phi_i - dpsi), tj = my_wrap(phi_j - dpsi);
  const double mi = -(k.beta * l0 * l0 / 2) * tj + k.delta * l0 * l0 * (tj - ti);
  const double mj = -(k.beta * l0 * l0 / 2) * ti + k.delta * l0 * l0 * (ti - tj);
  const double q = (mi + mj) / l;
  const double fa = k.alpha * (l - l0);
  // Energy: ½α(l − l0)² + the bending quadratic form whose derivatives are −M_i, −M_j.
  const double e = 0.5 * k.alpha * (l - l0) * (l - l0) +
                   l0 * l0 * (0.5 * k.delta * (ti * ti + tj * tj) + (0.5 * k.beta - k.delta) * ti * tj);
  return {fa * ex + q * tx, fa * ey + q * ty, mi, mj, e, (l - l0) / l0, ti, tj};
}

TEST(DemBeam, CoRotationalLawOfTheNote) {
  // Random orientations, strains of ±(0.1..5)%, transverse offsets and end rotations up to 0.3 rad.
  frac::Rng rng(3);
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  double worst = 0;
  for (int n = 0; n < 2000; ++n) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    const double turn = (rng.uniform() - 0.5) * 2 * kPi;  // current axis, anywhere
    double strain = 0.001 + 0.049 * rng.uniform();
    if (rng.uniform() < 0.5) strain = -strain;
    const double l = kL0 * (1 + strain);
    const double dx = l * std::cos(psi0 + turn), dy = l * std::sin(psi0 + turn);
    const double phi_i = turn + 0.3 * (rng.uniform() - 0.5) * 2, phi_j = turn + 0.3 * (rng.uniform() - 0.5) * 2;
    const BeamResponse r = beam_response(dx, dy, e0x, e0y, phi_i, phi_j, kL0, k);
    const Expected x = note_law(dx, dy, psi0, phi_i, phi_j, kL0, k);
    const double fs = std::max({std::hypot(x.fx, x.fy), std::abs(x.mi) / kL0, std::abs(x.mj) / kL0});
    const double err = std::max({std::abs(r.fx - x.fx), std::abs(r.fy - x.fy), std::abs(r.torque_i - x.mi) / kL0,
                                 std::abs(r.torque_j - x.mj) / kL0}) /
                       fs;
    worst = std::max(worst, err);
    ASSERT_LT(err, 1e-12) << "n = " << n;
    EXPECT_LT(rel(r.energy, x.energy), 1e-12);
    EXPECT_LT(rel(r.strain, x.strain), 1e-12);
    EXPECT_NEAR(r.theta_i, x.ti, 1e-14);
    EXPECT_NEAR(r.theta_j, x.tj, 1e-14);
    // Validation E5: M_i + M_j + (l e) × F_j = 0 with F_j = −F_i (to round-off of the moment scale).
    const double balance = r.torque_i + r.torque_j - (dx * r.fy - dy * r.fx);
    EXPECT_LT(std::abs(balance), 1e-13 * fs * kL0);
  }
  std::printf("[ beam     ] co-rotational law against the note: worst relative error %.2e\n", worst);
}

// The linear form of §4 in a frame fixed along i→j (= x here): Δv = u_y^j − u_y^i, Θ = cell rotations.
struct Linear {
  double fx, fy, mi, mj, force_scale, moment_scale;
};
Linear linear_form(double u, double dv, double phi_i, double phi_j, double l, const BeamStiffness& k) {
  Linear o;
  o.fx = k.alpha * u;
  o.fy = k.beta * dv - (k.beta * l / 2) * (phi_i + phi_j);
  o.mi = (k.beta * l / 2) * (dv - l * phi_j) + k.delta * l * l * (phi_j - phi_i);
  o.mj = (k.beta * l / 2) * (dv - l * phi_i) + k.delta * l * l * (phi_i - phi_j);
  // Sum of the magnitudes of the terms: the scale against which a relative error is measured (a
  // component that cancels to zero is then still checked, against the size of its parts).
  o.force_scale = k.alpha * std::abs(u) + k.beta * std::abs(dv) + k.beta * l / 2 * (std::abs(phi_i) + std::abs(phi_j));
  o.moment_scale = l * o.force_scale + k.delta * l * l * (std::abs(phi_i) + std::abs(phi_j));
  return o;
}

void expect_linear(double u_rel, double dv_rel, double phi_i, double phi_j, const char* what) {
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  const double dx = kL0 + u_rel * kL0, dy = dv_rel * kL0;
  const double u = dx - kL0;  // the displacement actually represented (exact: Sterbenz)
  const BeamResponse r = beam_response(dx, dy, 1.0, 0.0, phi_i, phi_j, kL0, k);
  const Linear x = linear_form(u, dy, phi_i, phi_j, kL0, k);
  const double efx = std::abs(r.fx - x.fx) / x.force_scale, efy = std::abs(r.fy - x.fy) / x.force_scale;
  const double emi = std::abs(r.torque_i - x.mi) / x.moment_scale, emj = std::abs(r.torque_j - x.mj) / x.moment_scale;
  std::printf("[ beam     ] %-34s relative errors vs the linear form: Fx %.1e Fy %.1e Mi %.1e Mj %.1e\n", what, efx,
              efy, emi, emj);
  EXPECT_LT(efx, 1e-9) << what;
  EXPECT_LT(efy, 1e-9) << what;
  EXPECT_LT(emi, 1e-9) << what;
  EXPECT_LT(emj, 1e-9) << what;
}

TEST(DemBeam, SmallDisplacementsGiveTheLinearForm) {
  constexpr double eps = 1e-10;
  expect_linear(eps, 0, 0, 0, "axial stretch");
  expect_linear(-eps, 0, 0, 0, "axial compression");
  expect_linear(0, eps, 0, 0, "shear (transverse offset)");
  expect_linear(0, 0, eps, 0, "bending (rotation of i)");
  expect_linear(0, 0, 0, -eps, "bending (rotation of j)");
  expect_linear(0, 0, eps, -eps, "antisymmetric bending");
  expect_linear(0.7 * eps, -0.4 * eps, 1.3 * eps, 0.6 * eps, "combined");
}

TEST(DemBeam, SmallDisplacementSigns) {
  // Stretched: i is pulled toward j (+x); compressed: pushed away (beams act in compression too).
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  EXPECT_GT(beam_response(kL0 * 1.01, 0, 1, 0, 0, 0, kL0, k).fx, 0);
  EXPECT_LT(beam_response(kL0 * 0.99, 0, 1, 0, 0, 0, kL0, k).fx, 0);
  // j moved up: i is dragged up.
  EXPECT_GT(beam_response(kL0, 1e-6, 1, 0, 0, 0, kL0, k).fy, 0);
  // i turned counter-clockwise: its moment turns it back (clockwise).
  EXPECT_LT(beam_response(kL0, 0, 1, 0, 1e-6, 0, kL0, k).torque_i, 0);
}

TEST(DemBeam, CantileverDeflection) {
  // i clamped (fixed, φ_i = 0), tip load P on j (transverse, +y), j free to rotate. Timoshenko:
  // w = P l³/(3EI) + P l/(GA) and tip rotation P l²/(2EI). In that state the beam must pull j back with
  // −P, hold no moment at the free end, and the clamp moment is P·l. P is chosen so that w = 1e-10·l0
  // (linear regime, see the header), and M_j = 0 is checked against the scale P·l0.
  for (double s_over_l : {0.2, 0.57, 1.0}) {
    const double S = s_over_l * kL0;
    const BeamStiffness k = beam_stiffness(kL0, S, kH, kE, kShearRatio);
    const double EI = kE * kH * S * S * S / 12, GA = kE / kShearRatio * S * kH;
    const double compliance = kL0 * kL0 * kL0 / (3 * EI) + kL0 / GA;
    const double P = 1e-10 * kL0 / compliance;
    const double w = P * compliance, tip = P * kL0 * kL0 / (2 * EI);
    const BeamResponse r = beam_response(kL0, w, 1, 0, 0.0, tip, kL0, k);
    // Force on j is −(fx, fy); equilibrium with the load: −fy + P = 0.
    EXPECT_LT(std::abs(r.fy - P) / P, 1e-9) << "S/l0 = " << s_over_l;
    EXPECT_LT(std::abs(r.fx) / P, 1e-9);
    EXPECT_LT(std::abs(r.torque_j) / (P * kL0), 1e-9);
    EXPECT_LT(std::abs(r.torque_i - P * kL0) / (P * kL0), 1e-9);
  }
}

TEST(DemBeam, CarryOverFactor) {
  // Pure end rotation θ at i, j held: |M_i| = δ l² θ and M_j/M_i = (2 − Φ)/(4 + Φ), Φ = 2 S²/l0² (G = E/2);
  // slender beams tend to the classical 1/2. No displacement, so the law is linear in θ: 1e-12.
  for (double s_over_l : {0.01, 0.2, 0.57, 1.0}) {
    const double S = s_over_l * kL0;
    const BeamStiffness k = beam_stiffness(kL0, S, kH, kE, kShearRatio);
    const double theta = 1e-3, phi = 2 * S * S / (kL0 * kL0);
    const BeamResponse r = beam_response(kL0, 0, 1, 0, theta, 0, kL0, k);
    EXPECT_LT(rel(-r.torque_i, k.delta * kL0 * kL0 * theta), 1e-12);
    // (Absolute on the ratio, at most 1/2 and 0 at S = l0: round-off of M_j against M_i, not against zero.)
    EXPECT_NEAR(r.torque_j / r.torque_i, (2 - phi) / (4 + phi), 5e-13) << "S/l0 = " << s_over_l;
  }
  const BeamStiffness slender = beam_stiffness(kL0, 1e-3 * kL0, kH, kE, kShearRatio);
  const BeamResponse r = beam_response(kL0, 0, 1, 0, 1e-3, 0, kL0, slender);
  EXPECT_NEAR(r.torque_j / r.torque_i, 0.5, 1e-5);
}

TEST(DemBeam, RigidRotationMakesNoForce) {
  // Validation E4. Reference axis in a random direction; the pair turned rigidly by ω (both cells by
  // ω, the axis by ω) for angles up to π either way and several turns. Force scale: the axial force at
  // the breaking strain t_ε = 3%, α·l0·0.03 (the largest axial force a beam carries). Round-off: the
  // turned length is l0(1 ± 1e-16) and the accumulated angle φ = ω + 2πk carries ~1e-14 after a few
  // turns, both ~1e-12 of the scale or less.
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  const double scale = k.alpha * kL0 * 0.03;
  frac::Rng rng(5);
  std::vector<double> angles{1e-9, 1e-3, 0.5, 1.0, 2.0, 3.0, 3.14159, kPi, -kPi, -3.0, -1.0};
  for (int t = -3; t <= 3; ++t)
    for (double a : {0.7, kPi, 2.9}) angles.push_back(a + 2 * kPi * t);
  for (int n = 0; n < 200; ++n) angles.push_back((rng.uniform() - 0.5) * 2 * kPi);
  double worst = 0;
  for (int o = 0; o < 8; ++o) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    for (double w : angles) {
      const double c = std::cos(w), s = std::sin(w);
      const double dx = kL0 * (c * e0x - s * e0y), dy = kL0 * (s * e0x + c * e0y);
      const BeamResponse r = beam_response(dx, dy, e0x, e0y, w, w, kL0, k);
      const double err =
          std::max({std::abs(r.fx), std::abs(r.fy), std::abs(r.torque_i) / kL0, std::abs(r.torque_j) / kL0}) / scale;
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-9) << "ω = " << w << ", ψ0 = " << psi0;
      EXPECT_LT(std::abs(r.energy), 1e-18 * scale * kL0);
      EXPECT_EQ(breaking_mode(r.strain, r.theta_i, r.theta_j, 0.03, 0.0698), 0);
    }
  }
  std::printf("[ beam     ] rigid rotations (%zu angles x 8 axes): worst |F|/(α l0 t_eps) = %.2e\n", angles.size(),
              worst);
}

TEST(DemBeam, RigidRotationOfADeformedPairTurnsItsForces) {
  // Objectivity: a deformed pair (strain within ±1%, axis tilt and end rotations within ±0.025 rad)
  // turned by ω gives the same forces turned by ω and the same moments. Round-off: the turned separation
  // changes l by ~1e-16·l0, i.e. the axial force by α·l0·1e-16, against a force scale that includes the
  // bending terms (≥ ~δ·l0·1e-3 in these draws): ≤ ~1e-12 relative. 1e-11.
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  frac::Rng rng(9);
  double worst = 0;
  for (int n = 0; n < 500; ++n) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    const double l = kL0 * (1 + 0.02 * (rng.uniform() - 0.5)), tilt = 0.05 * (rng.uniform() - 0.5);
    const double dx = l * std::cos(psi0 + tilt), dy = l * std::sin(psi0 + tilt);
    const double pi = 0.05 * (rng.uniform() - 0.5), pj = 0.05 * (rng.uniform() - 0.5);
    const BeamResponse a = beam_response(dx, dy, e0x, e0y, pi, pj, kL0, k);
    const double w = (rng.uniform() - 0.5) * 8 * kPi, c = std::cos(w), s = std::sin(w);
    const BeamResponse b = beam_response(c * dx - s * dy, s * dx + c * dy, e0x, e0y, pi + w, pj + w, kL0, k);
    const double fs = std::max({std::hypot(a.fx, a.fy), std::abs(a.torque_i) / kL0, std::abs(a.torque_j) / kL0});
    const double err = std::max({std::abs(b.fx - (c * a.fx - s * a.fy)), std::abs(b.fy - (s * a.fx + c * a.fy)),
                                 std::abs(b.torque_i - a.torque_i) / kL0, std::abs(b.torque_j - a.torque_j) / kL0}) /
                       fs;
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-11) << "n = " << n;
  }
  std::printf("[ beam     ] deformed pair turned rigidly: worst relative change of its turned forces %.2e\n", worst);
}

TEST(DemBeam, ForcesAreMinusTheEnergyGradient) {
  // Central differences of beam_response().energy in (x_i, y_i, φ_i, x_j, y_j, φ_j), d = c_j − c_i.
  // Steps h = 1e-6·l0 and 1e-6 rad: truncation ~h²·E''' ~ 1e-12 of the force and round-off
  // ~1e-16·E/h ~ 1e-12 of it at strains of ~1%, so 1e-7 of the force scale leaves a wide margin while
  // any wrong sign or factor in a single term (≥ 1e-3 of the scale here) fails.
  const BeamStiffness k = beam_stiffness(kL0, kS, kH, kE, kShearRatio);
  frac::Rng rng(21);
  double worst = 0;
  for (int n = 0; n < 300; ++n) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    const double turn = (rng.uniform() - 0.5) * 2;
    const double l = kL0 * (1 + 0.04 * (rng.uniform() - 0.5)), tilt = 0.04 * (rng.uniform() - 0.5);
    std::array<double, 6> x{0.0,
                            0.0,
                            turn + 0.04 * (rng.uniform() - 0.5),
                            l * std::cos(psi0 + turn + tilt),
                            l * std::sin(psi0 + turn + tilt),
                            turn + 0.04 * (rng.uniform() - 0.5)};
    auto energy = [&](const std::array<double, 6>& s) {
      return beam_response(s[3] - s[0], s[4] - s[1], e0x, e0y, s[2], s[5], kL0, k).energy;
    };
    const BeamResponse r = beam_response(x[3] - x[0], x[4] - x[1], e0x, e0y, x[2], x[5], kL0, k);
    const std::array<double, 6> f{r.fx, r.fy, r.torque_i, -r.fx, -r.fy, r.torque_j};
    const double fs = std::max({std::hypot(r.fx, r.fy), std::abs(r.torque_i) / kL0, std::abs(r.torque_j) / kL0});
    for (int c = 0; c < 6; ++c) {
      const bool angle = c == 2 || c == 5;
      const double h = angle ? 1e-6 : 1e-6 * kL0;
      auto p = x, m = x;
      p[c] += h;
      m[c] -= h;
      const double grad = (energy(p) - energy(m)) / (p[c] - m[c]);
      const double err = std::abs(f[c] + grad) / (angle ? fs * kL0 : fs);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-7) << "coordinate " << c << ", n = " << n;
    }
  }
  std::printf("[ beam     ] forces vs −∇energy (central differences): worst relative error %.2e\n", worst);
}

TEST(DemBeam, BreakingRule) {
  const double te = 0.03, tt = 4 * kPi / 180;
  // Stretching alone: breaks past t_ε (mode 1), holds below.
  EXPECT_EQ(breaking_mode(1.001 * te, 0, 0, te, tt), 1);
  EXPECT_EQ(breaking_mode(te, 0, 0, te, tt), 1);  // "≥ 1"
  EXPECT_EQ(breaking_mode(0.999 * te, 0, 0, te, tt), 0);
  // Bending alone (a barely stretched beam): breaks past t_Θ at either end (mode 2), holds below.
  EXPECT_EQ(breaking_mode(1e-12, 1.001 * tt, 0, te, tt), 2);
  EXPECT_EQ(breaking_mode(1e-12, 0, -1.001 * tt, te, tt), 2);
  EXPECT_EQ(breaking_mode(1e-12, 0.999 * tt, -0.999 * tt, te, tt), 0);
  // The bending term is linear, not squared: (ε/t_ε)² + max|Θ|/t_Θ = 0.5² + 0.75 = 1 breaks, 0.74 does not.
  EXPECT_NE(breaking_mode(0.5 * te, 0.76 * tt, 0, te, tt), 0);
  EXPECT_EQ(breaking_mode(0.5 * te, 0.74 * tt, 0, te, tt), 0);
  // Compressed or unstrained: never, however large the strain or the bending.
  for (double eps : {0.0, -1e-12, -0.01, -0.5, -0.99})
    for (double th : {0.0, 0.5 * tt, 2 * tt, 1.0, kPi}) {
      EXPECT_EQ(breaking_mode(eps, th, -th, te, tt), 0) << eps << " " << th;
    }
}

}  // namespace

namespace {

// The fast paths of the beam loops (lib/geometry/angle.hpp, beam_response_near_reference, the breaking
// pre-check) against the exact forms. atan2_near_zero: a rational approximation good to ~1e-16 relative
// plus one rounded division: 4 ulp allows twice the worst case measured (2 ulp over 10^7 draws).
TEST(DemBeam, Atan2NearZeroAgreesWithLibrary) {
  using frac::geometry::atan2_near_zero;
  frac::Rng rng(5);
  double worst_ulp = 0;
  for (int k = 0; k < 200000; ++k) {
    const double scale = std::pow(10.0, -12 * rng.uniform());
    const double x = 0.5 + rng.uniform(), y = (rng.uniform() - 0.5) * 0.83 * x * scale;
    const double exact = std::atan2(y, x), fast = atan2_near_zero(y, x);
    const double ulp = std::nextafter(std::abs(exact), 1e300) - std::abs(exact);
    worst_ulp = std::max(worst_ulp, std::abs(fast - exact) / ulp);
  }
  EXPECT_LE(worst_ulp, 4.0);
  // Outside |y| ≤ tan(π/8)·x, x > 0 it is the library's atan2, bit for bit.
  for (double y : {0.5, -0.5, 1.0, 1e300, -0.0, 0.0})
    for (double x : {1.0, -1.0, 0.0, -0.0, 1e-300})
      if (!(x > 0 && std::abs(y) <= 0.41421356237309503 * x)) {
        EXPECT_EQ(atan2_near_zero(y, x), std::atan2(y, x)) << y << " " << x;
      }
  EXPECT_EQ(atan2_near_zero(0.0, 1.0), 0.0);
  std::printf("[ beam     ] atan2_near_zero vs std::atan2: worst %.1f ulp\n", worst_ulp);
}

// Where the branch-free formula says it applies, it is beam_response bit for bit; it declines rotations
// beyond π/8 and end angles outside (−π, π] (which need the wrap).
TEST(DemBeam, NearReferenceFormulaEqualsExactResponse) {
  const BeamStiffness k = beam_stiffness(kL0, 0.01, kH, kE, kShearRatio);
  frac::Rng rng(8);
  int covered = 0, declined = 0;
  for (int n = 0; n < 20000; ++n) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double turn = (rng.uniform() - 0.5) * 1.2;  // up to ±34°: some beyond π/8
    const double l = kL0 * (0.8 + 0.4 * rng.uniform());
    const double phi_i = (rng.uniform() - 0.5) * 8, phi_j = (rng.uniform() - 0.5) * 8;  // some beyond ±π
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    const double dx = l * std::cos(psi0 + turn), dy = l * std::sin(psi0 + turn);
    BeamResponse fast;
    const bool near = frac::dem::beam_response_near_reference(dx, dy, e0x, e0y, phi_i, phi_j, kL0, k, fast);
    const BeamResponse exact = beam_response(dx, dy, e0x, e0y, phi_i, phi_j, kL0, k);
    // Clearly inside its range (π/8 = 0.3927, π = 3.1416): it must apply.
    const bool expected = std::abs(turn) < 0.39 && std::abs(phi_i - turn) < 3.1 && std::abs(phi_j - turn) < 3.1;
    if (near) {
      ++covered;
      EXPECT_EQ(fast.fx, exact.fx);
      EXPECT_EQ(fast.fy, exact.fy);
      EXPECT_EQ(fast.torque_i, exact.torque_i);
      EXPECT_EQ(fast.torque_j, exact.torque_j);
      EXPECT_EQ(fast.energy, exact.energy);
    } else {
      ++declined;
      EXPECT_FALSE(expected) << "turn " << turn << " phi " << phi_i << " " << phi_j;
    }
  }
  EXPECT_GT(covered, 1000);
  EXPECT_GT(declined, 1000);
}

// The breaking pass's pre-check (no atan2 where the verdict is certain) gives the exact rule's verdict
// and energy, including states within 1e-6 of the threshold.
TEST(DemBeam, BreakingPrecheckGivesExactVerdict) {
  const BeamStiffness k = beam_stiffness(kL0, 0.01, kH, kE, kShearRatio);
  const double te = 0.03, tt = 4 * kPi / 180;
  frac::Rng rng(13);
  int breaks = 0, near_threshold = 0;
  for (int n = 0; n < 50000; ++n) {
    const double psi0 = (rng.uniform() - 0.5) * 2 * kPi;
    const double turn = (rng.uniform() - 0.5) * (n % 5 == 0 ? 7.0 : 0.2);
    const double strain = (rng.uniform() - 0.3) * 0.05;
    const double phi_i = (rng.uniform() - 0.5) * 0.2, phi_j = (rng.uniform() - 0.5) * 0.2;
    const double l = kL0 * (1 + strain);
    const double e0x = std::cos(psi0), e0y = std::sin(psi0);
    const double dx = l * std::cos(psi0 + turn), dy = l * std::sin(psi0 + turn);
    const BeamResponse r = beam_response(dx, dy, e0x, e0y, phi_i, phi_j, kL0, k);
    const int exact = breaking_mode(r.strain, r.theta_i, r.theta_j, te, tt);
    double energy = -1;
    const int fast = breaking_mode(dx, dy, e0x, e0y, phi_i, phi_j, kL0, k, te, tt, energy);
    ASSERT_EQ(fast, exact) << "strain " << r.strain << " turn " << turn;
    if (exact != 0) {
      ++breaks;
      EXPECT_EQ(energy, r.energy);
    }
    const double rule = (r.strain / te) * (r.strain / te) + std::max(std::abs(r.theta_i), std::abs(r.theta_j)) / tt;
    if (r.strain > 0 && std::abs(rule - 1) < 1e-2) ++near_threshold;
  }
  EXPECT_GT(breaks, 1000);
  EXPECT_GT(near_threshold, 100);
}

}  // namespace
