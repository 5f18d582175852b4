#pragma once
// Predicted wave speeds of the polygon DEM from its measured elastic constants, and the propagation
// directions wave-speed understands.
//
// The DEM sample is a slab in plane stress (physics/polygon-dem.md §8.1: Young modulus K from the slope
// of sigma(eps), Poisson ratio nu from the lateral contraction). For an isotropic linear-elastic plate in
// plane stress with 3D density rho (kg/m^3; the slab thickness cancels):
//   c_L = sqrt(K / (rho (1 - nu^2)))     longitudinal (P) waves
//   c_S = sqrt(K / (2 rho (1 + nu)))     shear (S) waves, = sqrt(G/rho) with G = K / (2(1 + nu))
//   c_0 = sqrt(K / rho)                  bar speed (a thin strip loaded along its length), for reference
#include <string>

namespace frac::analysis {

struct PlaneStressSpeeds {
  double longitudinal = 0, shear = 0, bar = 0;  // m/s
};
// UsageError for K <= 0, rho <= 0 or nu outside (-1, 1).
PlaneStressSpeeds plane_stress_speeds(double young, double poisson, double density);

// A direction in the plane, given as "x", "y", "-x", "-y" or an angle in degrees from +x
// ("40", "-30", "40deg"), or "radial" (outward from a point source; returned as NaN, see
// analysis/wave_speed.hpp). Returns radians in (-pi, pi]. UsageError naming `option` otherwise.
double parse_direction(const std::string& text, const std::string& option);
// "x", "y", "-x", "-y" for the axes, "radial" for NaN, else the angle in degrees ("40deg"): used in
// output keys.
std::string direction_label(double radians);

}  // namespace frac::analysis
