#include "core/finite.hpp"

#include <algorithm>

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

bool all_finite(std::span<const double> x, std::size_t blocks) { return all_finite(x, {}, blocks); }

bool all_finite(std::span<const double> x, std::span<const double> y, std::size_t blocks) {
  return sum_over_coordinate_ranges(std::max(x.size(), y.size()), blocks, [&](std::size_t first, std::size_t last) {
           return zero_sum(x.data(), first, std::min(last, x.size())) +
                  zero_sum(y.data(), first, std::min(last, y.size()));
         }) == 0.0;
}

}  // namespace frac
