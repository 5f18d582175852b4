#pragma once
// Runaway detection: a run whose bodies leave the neighbourhood of where they started stops with the
// step and the body named, instead of writing positions of 1e146 m. Fragments of the hardest scenes
// travel a few mesh sizes in a run; a body 1000 mesh sizes away comes from an energy or a time step the
// scene cannot resolve. Checked where a run takes its observables: one pass over the positions.
#include <array>
#include <cstdint>
#include <span>
#include <string>

namespace frac::dynamics {

class RunawayGuard {
 public:
  // `q0`: x of the n bodies, then y (then anything else); `body`: "cell" or "node", for messages.
  RunawayGuard(std::span<const double> q0, std::size_t n, std::string body);
  // RuntimeError naming the step, the time and the first body outside the bound (or not finite).
  void check(std::span<const double> q, std::int64_t step, double t) const;

  static constexpr double mesh_sizes = 1000;

 private:
  std::size_t n_;
  std::string body_;
  std::array<double, 2> centre_{};
  double limit_ = 0;
};

}  // namespace frac::dynamics
