#pragma once
// Long-wavelength wave speeds and stresses of the Mooney-Rivlin sheet W = rho a (J1 + b J2)
// (physics/rubber-lattice.md §4), and the check that Marder's lattice at a given stretch is Mooney-Rivlin
// at all: every bond family must be longer than Delta + u_s (branch 2 of the pair term) and far enough
// below the cut-off u_c (rubber-lattice-validation.md §D: u_c >= u + 15 w). Outside that range the
// lattice is a different material and its speeds must not be compared with these formulas.
//
// With F = diag(lx, ly), J = lx ly and a lab propagation direction n (unit), the acoustic tensor
// Q/rho = a[(1 - b/2)|k|^2 I + (b/2) J^2 k_lab k_lab^T], k_lab = F^-T k, gives one exactly transverse
// and one exactly longitudinal mode:
//   c_T^2 = a (1 - b/2) |F^T n|^2
//   c_L^2 = a [(1 - b/2) |F^T n|^2 + (b/2) J^2]
// These are lab speeds (distance in the stretched sheet per time). The reference-frame speeds
// omega/|k_ref| are the lab speeds divided by |F^T n| (the stretch along x or y for those directions).
// The density does not enter the speeds (W is proportional to rho); it sets the stresses.
#include <array>
#include <string>
#include <string_view>

namespace frac::analysis {

struct MooneyRivlin {
  double a = 1.0;        // m^2 s^-2 (a velocity squared)
  double b = 0.0;        // dimensionless; real shear speeds need b < 2
  double density = 1.0;  // kg m^-2, areal mass density of the reference (unstretched) sheet
};

struct Stretch {
  double x = 1.0, y = 1.0;  // extension ratios lambda_x, lambda_y (> 0)
};

// UsageError naming the quantity for a <= 0, density <= 0, non-finite b, or a stretch <= 0.
void validate(const MooneyRivlin& m, Stretch s);

struct MrWaveSpeeds {
  double direction = 0;               // rad, lab propagation direction measured from +x
  double longitudinal = 0;            // m/s, lab; NaN when c_L^2 <= 0
  double shear = 0;                   // m/s, lab; NaN when c_T^2 <= 0 (b >= 2)
  double longitudinal_reference = 0;  // m/s, omega/|k_ref| = lab / |F^T n|
  double shear_reference = 0;
  double stretch_along = 1;  // |F^T n|
};
MrWaveSpeeds mooney_rivlin_speeds(const MooneyRivlin& m, Stretch s, double direction);

// The Mach angle of a source running along x at lab speed `speed` (m/s): the angle alpha in (0, 90°] to x of
// the straight front it drags behind it, steady in the source's frame when speed · sin(alpha) = c(n), c the
// mode's lab speed along the front's normal n = (sin alpha, cos alpha). In an isotropic sheet this is
// asin(c/speed); here c depends on n. Radians; NaN when the source is not faster than the mode along x.
double mach_angle(const MooneyRivlin& m, Stretch s, double speed, bool longitudinal);

// Stresses of the homogeneously stretched sheet, force per length (N/m):
//   P_xx = rho a lx [1 + (b/2)(ly^2 - 1)],  P_yy = rho a ly [1 + (b/2)(lx^2 - 1)]  (Piola, per reference length)
//   sigma_xx = P_xx / ly, sigma_yy = P_yy / lx                                        (Cauchy, per current length)
struct MrStress {
  double piola_xx = 0, piola_yy = 0, cauchy_xx = 0, cauchy_yy = 0;
};
MrStress mooney_rivlin_stress(const MooneyRivlin& m, Stretch s);

// ---- Is the lattice Mooney-Rivlin at this stretch? ----

struct LatticeParameters {
  double spacing = 0;            // Delta, m (<= 0: unknown, nothing checked)
  std::string rows_along = "x";  // close-packed rows along "x" or "y" (mesh-gen triangular --rows-along)
  double short_width = -1;       // u_s: width of the short-bond branch 1, m (< 0: unknown)
  double cutoff = -1;            // u_c, m (< 0: unknown)
  double cutoff_width = -1;      // width of the Fermi cut-off h, m (< 0: unknown)
};

enum class LatticeRegime {
  mooney_rivlin,  // every bond in branch 2 and at least 15 cut-off widths below u_c
  short_bonds,    // a bond family shorter than Delta + u_s (branch 1): not Mooney-Rivlin
  near_cutoff,    // a bond family within 15 cut-off widths of u_c: the cut-off stiffens the far field
  broken,         // a bond family at or beyond u_c
  unchecked,      // Delta or u_s unknown: the branch-1 condition could not be checked
};
std::string_view name(LatticeRegime r);

// Cut-off clearance for a Mooney-Rivlin far field, in cut-off widths (rubber-lattice-validation.md §D:
// at u_c = u0 + 15 w the transverse speed is 0.5% above the continuum, at 12 w 7.5%, at 10 w 47%).
inline constexpr double kCutoffClearance = 15.0;

struct BondFamily {
  double reference_angle = 0;  // rad, direction of the family in the reference lattice
  double length = 0;           // m, length at the stretch (Delta |F d|)
};

struct LatticeCheck {
  LatticeRegime regime = LatticeRegime::unchecked;
  std::array<BondFamily, 3> families{};  // empty (length 0) when Delta is unknown
  std::string message;                   // one sentence naming the numbers
  // The continuum formulas describe the lattice (or could not be ruled out).
  bool comparable() const { return regime == LatticeRegime::mooney_rivlin || regime == LatticeRegime::unchecked; }
};
// UsageError for rows_along other than x or y, or a stretch <= 0.
LatticeCheck check_lattice(const LatticeParameters& p, Stretch s);

}  // namespace frac::analysis
