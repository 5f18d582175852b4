#include "core/finite.hpp"

#include "core/parallel.hpp"

namespace frac {
namespace {
// Σ p[k]·0 over [first, last), in four independent sums.
double zero_sum(const double* p, std::size_t first, std::size_t last) {
  double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  std::size_t k = first;
  for (; k + 4 <= last; k += 4) {
    c0 += p[k] * 0.0;
    c1 += p[k + 1] * 0.0;
    c2 += p[k + 2] * 0.0;
    c3 += p[k + 3] * 0.0;
  }
  for (; k < last; ++k) c0 += p[k] * 0.0;
  return c0 + c1 + c2 + c3;
}
}  // namespace

bool all_finite(std::span<const double> x, std::size_t blocks) {
  const double* p = x.data();
  const std::size_t n = x.size();
  if (n <= kMinParallelCoordinates) return zero_sum(p, 0, n) == 0.0;
  double s = 0;
#pragma omp parallel reduction(+ : s)
  this_thread_coordinate_ranges(n, blocks, [&](std::size_t first, std::size_t last) { s += zero_sum(p, first, last); });
  return s == 0.0;
}

}  // namespace frac
