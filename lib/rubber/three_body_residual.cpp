#include "rubber/three_body_residual.hpp"

#include <variant>

namespace frac::rubber {

std::vector<double> three_body_residual(const BondLaw& law, const Lattice& L, const Eigen::Matrix2d& F, double kappa) {
  std::vector<double> c(36, 0.0);
  const double d = L.spacing;
  for (int s = 0; s < 6; ++s)
    for (int t = 0; t < 6; ++t) {
      if (s == t) continue;
      const Eigen::Vector2d as = F * Eigen::Vector2d(L.slot_dir[2 * s], L.slot_dir[2 * s + 1]) * d;
      const Eigen::Vector2d at = F * Eigen::Vector2d(L.slot_dir[2 * t], L.slot_dir[2 * t + 1]) * d;
      const double X = as.dot(at);
      c[static_cast<std::size_t>(6 * s + t)] = kappa * std::visit([X](const auto& g) { return g(X).v; }, law.angle);
    }
  return c;
}

}  // namespace frac::rubber
