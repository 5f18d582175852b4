#pragma once
// atan2 for angles near zero, the common case of a beam's axis rotation: a rational approximation of
// atan on |y/x| ≤ tan(π/8) (Cephes atan, Moshier 1984: relative error ~1e-16 on |t| ≤ 0.66), a division
// and ten multiply-adds instead of the library call; elsewhere the library's atan2. Agrees with
// std::atan2 to a few units in the last place (tests/unit/test_angle.cpp), deterministic, branch-light.
#include <cmath>

namespace frac::geometry {

// The range of atan2_near_zero's own formula: x > 0 and |y| ≤ tan(π/8)·x.
inline bool atan2_in_near_zero_range(double y, double x) { return (x > 0) & (std::abs(y) <= 0.41421356237309503 * x); }

// atan(t) for |t| ≤ tan(π/8) (the rational approximation alone, no range test: branch-free).
inline double atan_near_zero(double t) {
  const double z = t * t;
  const double p =
      (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z - 7.500855792314704667340e1) * z -
       1.228866684490136173410e2) *
          z -
      6.485021904942025371773e1;
  const double q =
      ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z + 4.328810604912902668951e2) * z +
       4.853903996359136964868e2) *
          z +
      1.945506571482613964425e2;
  return t + t * (z * p / q);
}

inline double atan2_near_zero(double y, double x) {
  return atan2_in_near_zero_range(y, x) ? atan_near_zero(y / x) : std::atan2(y, x);
}

}  // namespace frac::geometry
