#pragma once
// Whether every value of an array is finite, the check a run makes on forces and states every step. x·0 is
// NaN for NaN and ±inf and 0 otherwise, so the sum of x·0 is 0 exactly when all are finite, in any order:
// an array of coordinates laid out in `blocks` equal blocks is summed by the threads as the integrator's
// loops split it (for_coordinate_ranges, core/parallel.hpp), so the values are read where they were
// written; a short one by one thread with four independent sums.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

namespace frac {

bool all_finite(std::span<const double> x, std::size_t blocks = 1);
// The same test in passing, inside a loop that computes the values: a word whose top bit is set when x is NaN or
// ±inf, to be OR-ed into a std::uint64_t with `omp simd reduction(| : ...)` and read by non_finite_seen. Integer
// operations alone (x's exponent field plus one unit of it carries into the top bit exactly when the field is all
// ones), which GCC 12 vectorises even on the baseline x86-64: a comparison turned into an int (!(x·0 == 0)) kept
// such loops scalar, and so did an `omp simd reduction(+)` on a double (Σ x·0) inside the thread helpers' lambdas.
inline std::uint64_t non_finite_bit(double x) {
  return (std::bit_cast<std::uint64_t>(x) & 0x7ff0000000000000u) + 0x0010000000000000u;
}
inline bool non_finite_seen(std::uint64_t bits) { return (bits >> 63) != 0; }
// Both arrays (of the same layout), in one pass of the threads.
bool all_finite(std::span<const double> x, std::span<const double> y, std::size_t blocks);

}  // namespace frac
