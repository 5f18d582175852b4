#pragma once
// The beam between two cell centroids (physics/polygon-dem.md §4, Herrmann-Hansen-Roux 1989):
// Timoshenko stiffnesses α, β, δ from the initial geometry, evaluated in the co-rotational frame of
// the current beam axis, so that a rigid motion of a bonded pair makes no force; and the breaking
// rule of §5. One beam at a time here; beams.hpp runs the loops.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/angle.hpp"

namespace frac::dem {

struct BeamStiffness {
  double alpha;  // axial, N/m: E S h / l0
  double beta;   // shear, N/m: 1/(b + c/12)
  double delta;  // bending, N/m: β (b/c + 1/3); moments are δ l0² Θ
};

// a = l0/(E S h), b = shear_ratio·a (the paper: b = 2a), c = l0³/(E I), I = h S³/12.
inline BeamStiffness beam_stiffness(double l0, double section, double thickness, double young, double shear_ratio) {
  if (young == 0) return {0, 0, 0};  // E = 0: no beam at all (the closed forms would give 0·∞/∞)
  const double a = l0 / (young * section * thickness);
  const double b = shear_ratio * a;
  const double c = l0 * l0 * l0 / (young * thickness * section * section * section / 12.0);
  const double beta = 1.0 / (b + c / 12.0);
  return {1.0 / a, beta, beta * (b / c + 1.0 / 3.0)};
}

// Wraps an angle into (−π, π].
inline double wrap_angle(double x) {
  constexpr double two_pi = 2 * std::numbers::pi;
  if (x > -std::numbers::pi && x <= std::numbers::pi) return x;
  x = std::remainder(x, two_pi);
  return x <= -std::numbers::pi ? x + two_pi : x;
}

// The state of one beam and the forces it makes. Inputs: centroid separation d = c_j − c_i, the unit
// initial axis e0, the cells' accumulated angles (0 in the reference state).
struct BeamResponse {
  double length;              // l, m
  double strain;              // ε = (l − l0)/l0
  double theta_i, theta_j;    // end rotations relative to the current axis, rad
  double fx, fy;              // force on i, N (j receives −F)
  double torque_i, torque_j;  // N m
  double energy;              // elastic energy, J
};

// The current beam axis: length l, unit vector e, and the rotation since the reference state e0 as
// sin Δψ = e0 × e and cos Δψ = e0 · e.
struct BeamAxis {
  double length, inv_length, ex, ey, sin_psi, cos_psi;
};
inline BeamAxis beam_axis(double dx, double dy, double e0x, double e0y) {
  const double l = std::sqrt(dx * dx + dy * dy);
  const double inv_l = 1.0 / l;
  const double ex = dx * inv_l, ey = dy * inv_l;
  return {l, inv_l, ex, ey, e0x * ey - e0y * ex, e0x * ex + e0y * ey};
}

// The response of a beam on `axis` whose ends are rotated by Θ_i, Θ_j from it.
inline BeamResponse beam_response_at(const BeamAxis& axis, double ti, double tj, double l0, const BeamStiffness& k) {
  BeamResponse r;
  const double l02 = l0 * l0;
  const double mi = -(k.beta * l02 / 2) * tj + k.delta * l02 * (tj - ti);
  const double mj = -(k.beta * l02 / 2) * ti + k.delta * l02 * (ti - tj);
  const double q = (mi + mj) * axis.inv_length;  // shear force along t = ẑ × e, from the moment balance
  const double stretch = axis.length - l0;
  const double fa = k.alpha * stretch;
  r.length = axis.length;
  r.strain = stretch / l0;
  r.theta_i = ti;
  r.theta_j = tj;
  r.fx = fa * axis.ex - q * axis.ey;
  r.fy = fa * axis.ey + q * axis.ex;
  r.torque_i = mi;
  r.torque_j = mj;
  r.energy = 0.5 * k.alpha * stretch * stretch +
             l02 * (0.5 * k.delta * (ti * ti + tj * tj) + (0.5 * k.beta - k.delta) * ti * tj);
  return r;
}

inline BeamResponse beam_response(double dx, double dy, double e0x, double e0y, double phi_i, double phi_j, double l0,
                                  const BeamStiffness& k) {
  const BeamAxis axis = beam_axis(dx, dy, e0x, e0y);
  // Rotation of the axis since the reference state, as a wrapped difference (never raw atan2 values);
  // it is small for an intact beam, where atan2_near_zero is fast.
  const double dpsi = geometry::atan2_near_zero(axis.sin_psi, axis.cos_psi);
  return beam_response_at(axis, wrap_angle(phi_i - dpsi), wrap_angle(phi_j - dpsi), l0, k);
}

// beam_response where it needs neither the library's atan2 nor a wrap (Δψ within ±π/8, Θ within
// (−π, π]): branch-free and without library calls, for the beam loop. Returns false, r unspecified, elsewhere;
// where it returns true, r is beam_response's, bit for bit.
inline bool beam_response_near_reference(double dx, double dy, double e0x, double e0y, double phi_i, double phi_j,
                                         double l0, const BeamStiffness& k, BeamResponse& r) {
  const BeamAxis axis = beam_axis(dx, dy, e0x, e0y);
  const double dpsi = geometry::atan_near_zero(axis.sin_psi / axis.cos_psi);
  const double ti = phi_i - dpsi, tj = phi_j - dpsi;
  r = beam_response_at(axis, ti, tj, l0, k);
  constexpr double pi = std::numbers::pi;
  return geometry::atan2_in_near_zero_range(axis.sin_psi, axis.cos_psi) & (ti > -pi) & (ti <= pi) & (tj > -pi) &
         (tj <= pi);
}

// Breaking rule, paper eq. 13: only a stretched beam breaks, when (ε/t_ε)² + max(|Θ_i|,|Θ_j|)/t_Θ ≥ 1.
// Returns 0 (holds), 1 (breaks, the stretching term dominates) or 2 (breaks, bending dominates).
inline int breaking_mode(double strain, double theta_i, double theta_j, double t_eps, double t_theta) {
  if (!(strain > 0)) return 0;
  const double s = (strain / t_eps) * (strain / t_eps);
  const double b = std::max(std::abs(theta_i), std::abs(theta_j)) / t_theta;
  if (s + b < 1) return 0;
  return s >= b ? 1 : 2;
}

// True when the beam in state (dx, dy, φ_i, φ_j) certainly holds under the breaking rule, decided without sqrt,
// atan2 or wrap, and without a branch (a vector loop runs it): a beam that is not stretched holds, and one whose
// strain and end rotations are bounded well inside the rule holds. The bounds: ε = (l − l0)/l0 ≤ (l² − l0²)/(2
// l0²) for l ≥ l0; |Θ| = |wrap(φ − Δψ)| ≤ |φ| + |Δψ| and |Δψ| ≤ |tan Δψ| = |e0 × d|/(e0 · d) while the axis has
// turned by less than π/2. The 1e-9 margins dwarf the round-off of the exact evaluation. False: the exact rule
// decides.
inline bool breaking_bound_holds(double dx, double dy, double e0x, double e0y, double phi_i, double phi_j, double l0,
                                 double t_eps, double t_theta) {
  const double l2 = dx * dx + dy * dy, l02 = l0 * l0;
  // (Not clamped at 0: squared, a negative bound only adds to a, and a select here would keep the loop scalar.)
  const double strain_bound = 0.5 * (l2 - l02) / l02 * (1 + 1e-9);
  const double s = e0x * dy - e0y * dx, c = e0x * dx + e0y * dy;  // |d| sin Δψ, |d| cos Δψ
  const double a =
      (strain_bound / t_eps) * (strain_bound / t_eps) + std::max(std::abs(phi_i), std::abs(phi_j)) / t_theta;
  return (l2 < l02 * (1 - 1e-12)) | ((c > 0) & (a * c + std::abs(s) / t_theta < (1 - 1e-9) * c));
}

// The exact rule on beam_response's values of the beam in state (dx, dy, φ_i, φ_j); `energy` receives its
// elastic energy.
inline int exact_breaking_mode(double dx, double dy, double e0x, double e0y, double phi_i, double phi_j, double l0,
                               const BeamStiffness& k, double t_eps, double t_theta, double& energy) {
  const BeamResponse r = beam_response(dx, dy, e0x, e0y, phi_i, phi_j, l0, k);
  energy = r.energy;
  return breaking_mode(r.strain, r.theta_i, r.theta_j, t_eps, t_theta);
}

// breaking_mode of the beam in state (dx, dy, φ_i, φ_j): 0 where breaking_bound_holds, else exact_breaking_mode
// (the same verdict and mode as the exact rule everywhere). `energy` receives the elastic energy of a beam
// that breaks.
inline int breaking_mode(double dx, double dy, double e0x, double e0y, double phi_i, double phi_j, double l0,
                         const BeamStiffness& k, double t_eps, double t_theta, double& energy) {
  if (breaking_bound_holds(dx, dy, e0x, e0y, phi_i, phi_j, l0, t_eps, t_theta)) return 0;
  return exact_breaking_mode(dx, dy, e0x, e0y, phi_i, phi_j, l0, k, t_eps, t_theta, energy);
}

}  // namespace frac::dem
