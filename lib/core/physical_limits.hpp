#pragma once
// Bounds on scene values beyond which no solid behaves as the models assume: values past them are a typo
// or a unit slip, refused (exit 2) rather than run to positions of 1e146 m. Each is far outside what any
// experiment of the toolkit uses.
namespace frac::limits {

inline constexpr double kSpeed = 1e5;      // m/s, any speed given or kicked: 30 x the hardest impact tested
inline constexpr double kDensity = 1e5;    // kg/m^3: 4 x osmium
inline constexpr double kModulus = 1e13;   // Pa: 10 x diamond
inline constexpr double kThickness = 1e3;  // m, the slab behind a 2D sample
inline constexpr double kRate = 1e9;       // s^-1, damping rates: faster ones force sub-nanosecond steps
inline constexpr double kStretch = 100;    // extension ratio of the rubber sheet (rubbers fail below 10)

}  // namespace frac::limits
