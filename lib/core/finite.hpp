#pragma once
// Whether every value of an array is finite, the check a run makes on forces and states every step. x·0 is
// NaN for NaN and ±inf and 0 otherwise, so the sum of x·0 is 0 exactly when all are finite, in any order:
// large arrays are summed by the threads (each its block, as the integrator's loops split them, so the
// values are read where they were written), small ones by one thread with four independent sums.
#include <span>

namespace frac {

bool all_finite(std::span<const double> x);

// Arrays at least this long are checked (and the model's per-coordinate loops run) by the threads; below,
// the fork and join cost more than the loop.
inline constexpr std::size_t kMinParallelArray = 16384;

}  // namespace frac
