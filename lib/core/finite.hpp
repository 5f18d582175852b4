#pragma once
// Whether every value of an array is finite, the check a run makes on forces and states every step. x·0 is
// NaN for NaN and ±inf and 0 otherwise, so the sum of x·0 is 0 exactly when all are finite, in any order:
// an array of coordinates laid out in `blocks` equal blocks is summed by the threads as the integrator's
// loops split it (for_coordinate_ranges, core/parallel.hpp), so the values are read where they were
// written; a short one by one thread with four independent sums.
#include <cstddef>
#include <span>

namespace frac {

bool all_finite(std::span<const double> x, std::size_t blocks = 1);
// The same test in passing, inside a loop that computes the values: 1 when x is NaN or ±inf (x·0 is not 0), to
// be OR-ed into an int with `omp simd reduction(| : ...)`. (An `omp simd reduction(+)` on a double, as Σ x·0,
// keeps GCC 12 from vectorising such a loop inside the thread helpers' lambdas; an integer one does not.)
inline int not_finite(double x) { return !(x * 0.0 == 0.0); }
// Both arrays (of the same layout), in one pass of the threads.
bool all_finite(std::span<const double> x, std::span<const double> y, std::size_t blocks);

}  // namespace frac
