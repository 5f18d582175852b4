#pragma once
// Portable random numbers: the same seed gives the same numbers on every platform and standard
// library (std::*_distribution does not). xoshiro256** seeded through splitmix64.
#include <cstdint>

namespace frac {

class Rng {
 public:
  explicit Rng(std::uint64_t seed);
  // Next raw 64-bit value.
  std::uint64_t next();
  // Uniform double in [0, 1) with 53 random bits.
  double uniform();
  // Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t s_[4];
};

}  // namespace frac
