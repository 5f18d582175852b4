#include "core/finite.hpp"

namespace frac {

bool all_finite(std::span<const double> x) {
  const double* p = x.data();
  const std::size_t n = x.size();
  if (n >= kMinParallelArray) {
    double s = 0;
#pragma omp parallel for simd schedule(static) reduction(+ : s)
    for (std::size_t k = 0; k < n; ++k) s += p[k] * 0.0;
    return s == 0.0;
  }
  double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    c0 += p[k] * 0.0;
    c1 += p[k + 1] * 0.0;
    c2 += p[k + 2] * 0.0;
    c3 += p[k + 3] * 0.0;
  }
  for (; k < n; ++k) c0 += p[k] * 0.0;
  return c0 + c1 + c2 + c3 == 0.0;
}

}  // namespace frac
