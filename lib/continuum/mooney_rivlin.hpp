#pragma once
// The continuum the rubber lattice stands for: a Mooney-Rivlin sheet, W/ρ = a (J1 + b J2) per unit
// reference area (physics/rubber-lattice.md §1, §4), with e = (FᵀF − I)/2, J1 = tr e, J2 = det e.
// Energy density, Piola stress, acoustic tensor and the long-wave speeds at a homogeneous stretch F,
// plus the lattice constants A, B that make the lattice reproduce it (§2). Pure functions, no state:
// the wave-speed analysis may call them for its predictions.
#include <Eigen/Core>
#include <Eigen/LU>

namespace frac::mr {

using Mat2 = Eigen::Matrix2d;
using Vec2 = Eigen::Vector2d;

struct Material {
  double a = 1;    // m^2 s^-2: W/ρ = a (J1 + b J2)
  double b = 1.5;  // dimensionless; real shear waves need b < 2
  double rho = 1;  // kg m^-2: areal mass density in the reference state
};

// J1 = tr e and J2 = det e of the Green strain e = (FᵀF − I)/2.
double j1(const Mat2& F);
double j2(const Mat2& F);
// W/ρ = a (J1 + b J2) (m^2 s^-2); times ρ gives the energy per reference area.
double energy_per_mass(const Mat2& F, double a, double b);
// First Piola-Kirchhoff stress dW/dF = ρa[(1 − b/2) F + (b/2) J cof F] (N m^-1: force per reference length).
Mat2 piola(const Mat2& F, const Material& m);
// Cauchy stress P Fᵀ / J (N m^-1: force per current length).
Mat2 cauchy(const Mat2& F, const Material& m);
// Acoustic tensor over ρ for a reference wavevector k: Q/ρ = a[(1 − b/2)|k|² I + (b/2) J² k_lab k_labᵀ],
// k_lab = F⁻ᵀ k; ω² U = (Q/ρ) U.
Mat2 acoustic_tensor(const Mat2& F, const Vec2& k_ref, double a, double b);

struct Speeds {
  double transverse = 0;    // m/s, lab frame; NaN when c_T² < 0 (b > 2)
  double longitudinal = 0;  // m/s, lab frame
};
// Long-wave lab speeds along the lab direction n (normalised inside):
// c_T² = a(1 − b/2)|Fᵀn|², c_L² = a[(1 − b/2)|Fᵀn|² + (b/2)J²].
Speeds speeds(const Mat2& F, const Vec2& n_lab, double a, double b);
inline Speeds speeds_x(double lx, double ly, double a, double b) {
  return speeds(Mat2{{lx, 0}, {0, ly}}, Vec2(1, 0), a, b);
}
inline Speeds speeds_y(double lx, double ly, double a, double b) {
  return speeds(Mat2{{lx, 0}, {0, ly}}, Vec2(0, 1), a, b);
}

// Lattice constants (§2): A = m a / Δ², B = 9 m a b / (8 Δ⁴), m = mass per node = (√3/2) ρ Δ².
double node_mass(double rho, double spacing);
double lattice_A(double node_mass, double a, double spacing);
double lattice_B(double node_mass, double a, double b, double spacing);

}  // namespace frac::mr
