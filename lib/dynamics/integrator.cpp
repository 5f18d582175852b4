#include "dynamics/integrator.hpp"

#include <string>

#include "core/error.hpp"

namespace frac::dynamics {

IntegratorKind parse_integrator_kind(std::string_view name, std::string_view option) {
  if (name == "gear5") return IntegratorKind::gear5;
  if (name == "verlet") return IntegratorKind::verlet;
  throw UsageError(std::string(option) + ": unknown integrator '" + std::string(name) +
                   "' (choose gear5 or verlet)");
}

std::string_view name(IntegratorKind kind) { return kind == IntegratorKind::gear5 ? "gear5" : "verlet"; }

double stability_limit(IntegratorKind kind) {
  // Largest ω·dt with spectral radius ≤ 1 of the step on ẍ = −ω²x: gear5 (c0 = 3/16) 0.3130, rounded
  // down; Verlet 2 (tests/unit/test_integrator.cpp re-measures both).
  return kind == IntegratorKind::gear5 ? 0.31 : 2.0;
}

double damping_limit(IntegratorKind kind) { return kind == IntegratorKind::gear5 ? 0.16 : 1.0; }

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind) {
  if (kind == IntegratorKind::gear5) return std::make_unique<Gear5>();
  return std::make_unique<VelocityVerlet>();
}

// ---------------------------------------------------------------- Gear5
namespace {
constexpr double kGearC[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
}

void Gear5::start(System& system, double t0, double dt, std::span<const double> q0, std::span<const double> v0) {
  n_ = q0.size();
  t_ = t0;
  dt_ = dt;
  steps_ = 0;
  for (auto& r : r_) r.assign(n_, 0.0);
  v_.assign(v0.begin(), v0.end());
  a_.assign(n_, 0.0);
  std::copy(q0.begin(), q0.end(), r_[0].begin());
  system.prescribe(t_, r_[0], v_, a_);
  system.accelerations(t_, r_[0], v_, a_);
  system.prescribe(t_, r_[0], v_, a_);
  for (std::size_t i = 0; i < n_; ++i) {
    r_[1][i] = dt * v_[i];
    r_[2][i] = 0.5 * dt * dt * a_[i];
  }
}

void Gear5::start_exact(System& system, double t0, double dt, const std::vector<std::vector<double>>& derivs) {
  start(system, t0, dt, derivs.at(0), derivs.at(1));
  double scale = dt * dt / 2;
  for (int k = 3; k <= 5; ++k) {
    scale *= dt / k;
    for (std::size_t i = 0; i < n_; ++i) r_[k][i] = scale * derivs.at(static_cast<std::size_t>(k))[i];
  }
}

void Gear5::set_velocity(std::size_t i, double value) {
  v_[i] = value;
  r_[1][i] = dt_ * value;
}

void Gear5::apply_prescribed(const System& system, double t) {
  const auto fixed = system.prescribed();
  if (fixed.empty()) return;
  system.prescribe(t, r_[0], v_, a_);
  for (std::size_t i : fixed) {
    r_[1][i] = dt_ * v_[i];
    r_[2][i] = 0.5 * dt_ * dt_ * a_[i];
    r_[3][i] = r_[4][i] = r_[5][i] = 0.0;
  }
}

void Gear5::step(System& system) {
  double* r0 = r_[0].data();
  double* r1 = r_[1].data();
  double* r2 = r_[2].data();
  double* r3 = r_[3].data();
  double* r4 = r_[4].data();
  const double* r5 = r_[5].data();
  const double inv_dt = 1.0 / dt_;
  // Predictor: Pascal's triangle, each line reading only not-yet-updated higher orders.
  for (std::size_t i = 0; i < n_; ++i) {
    r0[i] += r1[i] + r2[i] + r3[i] + r4[i] + r5[i];
    r1[i] += 2 * r2[i] + 3 * r3[i] + 4 * r4[i] + 5 * r5[i];
    r2[i] += 3 * r3[i] + 6 * r4[i] + 10 * r5[i];
    r3[i] += 4 * r4[i] + 10 * r5[i];
    r4[i] += 5 * r5[i];
    v_[i] = r1[i] * inv_dt;
  }
  t_ += dt_;
  apply_prescribed(system, t_);
  system.accelerations(t_, r_[0], v_, a_);
  // Corrector.
  const double half_dt2 = 0.5 * dt_ * dt_;
  double* r5w = r_[5].data();
  for (std::size_t i = 0; i < n_; ++i) {
    const double delta = half_dt2 * a_[i] - r2[i];
    r0[i] += kGearC[0] * delta;
    r1[i] += kGearC[1] * delta;
    r2[i] += kGearC[2] * delta;
    r3[i] += kGearC[3] * delta;
    r4[i] += kGearC[4] * delta;
    r5w[i] += kGearC[5] * delta;
    v_[i] = r1[i] * inv_dt;
  }
  apply_prescribed(system, t_);
  ++steps_;
}

// ---------------------------------------------------------------- velocity Verlet
void VelocityVerlet::start(System& system, double t0, double dt, std::span<const double> q0,
                           std::span<const double> v0) {
  n_ = q0.size();
  t_ = t0;
  dt_ = dt;
  steps_ = 0;
  q_.assign(q0.begin(), q0.end());
  v_.assign(v0.begin(), v0.end());
  a_.assign(n_, 0.0);
  v_est_.assign(n_, 0.0);
  system.prescribe(t_, q_, v_, a_);
  system.accelerations(t_, q_, v_, a_);
  system.prescribe(t_, q_, v_, a_);
}

void VelocityVerlet::step(System& system) {
  const double h = 0.5 * dt_;
  for (std::size_t i = 0; i < n_; ++i) {
    v_[i] += h * a_[i];        // half kick
    q_[i] += dt_ * v_[i];      // drift
    v_est_[i] = v_[i] + h * a_[i];  // velocity estimate at the new time for velocity-dependent forces
  }
  t_ += dt_;
  system.prescribe(t_, q_, v_est_, a_);
  system.accelerations(t_, q_, v_est_, a_);
  for (std::size_t i = 0; i < n_; ++i) v_[i] += h * a_[i];  // half kick
  const auto fixed = system.prescribed();
  if (!fixed.empty()) system.prescribe(t_, q_, v_, a_);
  ++steps_;
}

}  // namespace frac::dynamics
