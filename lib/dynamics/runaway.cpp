#include "dynamics/runaway.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace frac::dynamics {

RunawayGuard::RunawayGuard(std::span<const double> q0, std::size_t n, std::string body)
    : n_(n), body_(std::move(body)) {
  if (n == 0) return;
  std::array<double, 2> lo{q0[0], q0[n]}, hi = lo;
  for (std::size_t k = 0; k < n; ++k) {
    lo = {std::min(lo[0], q0[k]), std::min(lo[1], q0[n + k])};
    hi = {std::max(hi[0], q0[k]), std::max(hi[1], q0[n + k])};
  }
  centre_ = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])};
  // (a mesh of one body or one row has no size along a side: at least 1 mm)
  limit_ = mesh_sizes * std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-3});
}

void RunawayGuard::check(std::span<const double> q, std::int64_t step, double t) const {
  for (std::size_t k = 0; k < n_; ++k) {
    const double dx = q[k] - centre_[0], dy = q[n_ + k] - centre_[1];
    if (std::abs(dx) <= limit_ && std::abs(dy) <= limit_) continue;
    std::ostringstream msg;
    msg << "runaway at step " << step << " (t = " << t << " s): " << body_ << " " << k << " is at (" << q[k] << ", "
        << q[n_ + k] << ") m, more than " << mesh_sizes
        << " mesh sizes from where the mesh started; the loading or the time step is beyond what this scene resolves";
    throw RuntimeError(msg.str());
  }
}

}  // namespace frac::dynamics
