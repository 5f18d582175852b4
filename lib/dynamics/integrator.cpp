#include "dynamics/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/finite.hpp"
#include "core/parallel.hpp"

namespace frac::dynamics {

// The step loops are element by element (the same bits on any number of threads) and light: they run on
// the threads from kMinParallelCoordinates on, split as the model splits its cells (for_coordinate_ranges).
// (rubber-run runs its own thread pool and keeps the shared team to one thread, so these loops stay serial there.)

IntegratorKind parse_integrator_kind(std::string_view name, std::string_view option) {
  if (name == "gear5") return IntegratorKind::gear5;
  if (name == "verlet") return IntegratorKind::verlet;
  throw UsageError(std::string(option) + ": unknown integrator '" + std::string(name) + "' (choose gear5 or verlet)");
}

double read_time_step(Scene& scene, double t_max) {
  if (scene.text("integrator.dt", "auto") == "auto") return 0.0;
  const double dt = scene.positive("integrator.dt", 0.0);
  const double steps = t_max / dt;
  if (!(steps <= kMostSteps))
    scene.refuse("integrator.dt", format_value(steps) + " steps to reach stop.t_max = " + format_value(t_max) +
                                      " s, more than " + format_value(kMostSteps));
  return dt;
}

std::string_view name(IntegratorKind kind) { return kind == IntegratorKind::gear5 ? "gear5" : "verlet"; }

StartKind parse_start_kind(std::string_view name, std::string_view option) {
  if (name == "zero") return StartKind::zero;
  if (name == "exact") return StartKind::exact;
  throw UsageError(std::string(option) + ": unknown start '" + std::string(name) + "' (choose zero or exact)");
}

std::string_view name(StartKind start) { return start == StartKind::zero ? "zero" : "exact"; }

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

// ---------------------------------------------------------------- exact start
namespace {

// Collocation on s ∈ [−1, 1] (t = t0 + tau·s) at the Chebyshev points s_j = cos(π(j + ½)/N), and the
// inverse of their Vandermonde matrix: the monomial coefficients of the polynomial through values f_j
// are c_m = Σ_j inverse[m][j]·f_j (condition number ~1e3 for N = 10).
constexpr int kNodes = 10;
struct Collocation {
  double s[kNodes];
  double inverse[kNodes][kNodes];
  Collocation() {
    double a[kNodes][2 * kNodes] = {};
    for (int j = 0; j < kNodes; ++j) {
      s[j] = std::cos(3.14159265358979323846 * (j + 0.5) / kNodes);
      double p = 1;
      for (int m = 0; m < kNodes; ++m, p *= s[j]) a[j][m] = p;
      a[j][kNodes + j] = 1;
    }
    // Gauss-Jordan with partial pivoting on [V | I] gives [I | V^-1].
    for (int c = 0; c < kNodes; ++c) {
      int pivot = c;
      for (int r = c + 1; r < kNodes; ++r)
        if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
      for (int k = 0; k < 2 * kNodes; ++k) std::swap(a[c][k], a[pivot][k]);
      const double d = a[c][c];
      for (int k = 0; k < 2 * kNodes; ++k) a[c][k] /= d;
      for (int r = 0; r < kNodes; ++r) {
        if (r == c) continue;
        const double f = a[r][c];
        for (int k = 0; k < 2 * kNodes; ++k) a[r][k] -= f * a[c][k];
      }
    }
    for (int m = 0; m < kNodes; ++m)
      for (int j = 0; j < kNodes; ++j) inverse[m][j] = a[m][kNodes + j];
  }
};

// The monomial coefficients of the accelerations through the nodes: c[m·n + i] = Σ_j inverse[m][j]·a_j,i.
void fit_accelerations(const Collocation& col, const std::vector<std::vector<double>>& a, std::size_t n,
                       std::vector<double>& c) {
  for (int m = 0; m < kNodes; ++m)
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      for (int j = 0; j < kNodes; ++j) sum += col.inverse[m][j] * a[j][i];
      c[static_cast<std::size_t>(m) * n + i] = sum;
    }
}

// One Picard pass: the positions and velocities at the nodes from the polynomial of the accelerations,
// q(s) = q0 + tau·s·v0 + tau²·Σ c_m s^(m+2)/((m+1)(m+2)), v(s) = v0 + tau·Σ c_m s^(m+1)/(m+1).
// Returns the largest change of a position and the largest excursion from q0.
std::pair<double, double> integrate_at_nodes(const Collocation& col, std::span<const double> q0,
                                             std::span<const double> v0, double tau, const std::vector<double>& c,
                                             std::vector<std::vector<double>>& q, std::vector<std::vector<double>>& v) {
  const std::size_t n = q0.size();
  double change = 0, excursion = 0;
  for (int j = 0; j < kNodes; ++j) {
    const double s = col.s[j];
    for (std::size_t i = 0; i < n; ++i) {
      double u = 0, w = 0, p = s;  // p = s^(m+1)
      for (int m = 0; m < kNodes; ++m, p *= s) {
        const double cm = c[static_cast<std::size_t>(m) * n + i];
        w += cm * p / (m + 1);
        u += cm * p * s / ((m + 1) * (m + 2));
      }
      const double disp = tau * s * v0[i] + tau * tau * u;
      const double qn = q0[i] + disp;
      change = std::max(change, std::abs(qn - q[j][i]));
      excursion = std::max(excursion, std::abs(disp));
      q[j][i] = qn;
      v[j][i] = v0[i] + tau * w;
    }
  }
  return {change, excursion};
}

// The polynomial must resolve the motion: its two highest coefficients, relative to the largest, are
// ~(ω·tau)^9/9! (1e-15 at ω·tau = 0.1). Far above, the iteration still settles but on a polynomial
// that misses the derivatives.
void require_resolved(const std::vector<double>& c, std::size_t n) {
  double top = 0, all = 0;
  for (int m = 0; m < kNodes; ++m)
    for (std::size_t i = 0; i < n; ++i) {
      const double x = std::abs(c[static_cast<std::size_t>(m) * n + i]);
      all = std::max(all, x);
      if (m >= kNodes - 2) top = std::max(top, x);
    }
  if (top > 1e-8 * all)
    throw RuntimeError(
        "exact start: the time scale tau is too long for the fastest motion (the highest terms "
        "of the collocation polynomial are " +
        std::to_string(top / all) + " of its largest)");
}

// q0, v0 and d^(m+2)q/dt^(m+2) at s = 0, m!·c_m/tau^m, for m < 4.
void derivatives_at_start(std::span<const double> q0, std::span<const double> v0, double tau,
                          const std::vector<double>& c, std::vector<std::vector<double>>& derivs) {
  const std::size_t n = q0.size();
  derivs.assign(6, std::vector<double>(n));
  std::copy(q0.begin(), q0.end(), derivs[0].begin());
  std::copy(v0.begin(), v0.end(), derivs[1].begin());
  const double scale[4] = {1.0, 1.0 / tau, 2.0 / (tau * tau), 6.0 / (tau * tau * tau)};
  for (int m = 0; m < 4; ++m)
    for (std::size_t i = 0; i < n; ++i)
      derivs[static_cast<std::size_t>(m) + 2][i] = scale[m] * c[static_cast<std::size_t>(m) * n + i];
}

}  // namespace

TaylorStart taylor_derivatives(System& system, double t0, std::span<const double> q0, std::span<const double> v0,
                               double tau) {
  if (!(tau > 0) || !std::isfinite(tau)) throw UsageError("exact start: the time scale tau must be positive");
  static const Collocation col;
  const std::size_t n = q0.size();
  std::vector<std::vector<double>> q(kNodes), v(kNodes), a(kNodes);
  for (int j = 0; j < kNodes; ++j) {
    q[j].resize(n);
    v[j].assign(v0.begin(), v0.end());
    a[j].assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) q[j][i] = q0[i] + tau * col.s[j] * v0[i];
  }
  std::vector<double> c(kNodes * n);  // c[m·n + i]: coefficient of s^m of a_i(s)
  TaylorStart out;
  double rounding = 0;  // a few units in the last place of the largest coordinate
  for (double x : q0) rounding = std::max(rounding, 8 * std::numeric_limits<double>::epsilon() * std::abs(x));
  double previous = std::numeric_limits<double>::infinity();
  int stalled = 0;
  for (;;) {
    ++out.iterations;
    for (int j = 0; j < kNodes; ++j) {
      const double t = t0 + tau * col.s[j];
      system.prescribe(t, q[j], v[j], a[j]);
      system.accelerations(t, q[j], v[j], a[j]);
      system.prescribe(t, q[j], v[j], a[j]);
      ++out.evaluations;
    }
    fit_accelerations(col, a, n, c);
    const auto [change, excursion] = integrate_at_nodes(col, q0, v0, tau, c, q, v);
    out.residual = excursion > 0 ? change / excursion : 0.0;
    if (change <= rounding) break;  // the points moved by no more than the rounding of the coordinates
    if (!std::isfinite(out.residual) || (out.iterations > 4 && out.residual > previous && out.residual > 1e-6) ||
        out.iterations > 60)
      throw RuntimeError("exact start: the Picard iteration for the initial derivatives does not converge (change " +
                         std::to_string(out.residual) + " of the excursion after " + std::to_string(out.iterations) +
                         " passes); the time scale tau is too long");
    // Converged: nothing moves beyond 1e-15 of the excursion, or, once small, two passes in a row stopped
    // gaining (the rounding floor).
    if (out.residual <= 1e-15) break;
    stalled = out.residual < 1e-9 && out.residual > 0.5 * previous ? stalled + 1 : 0;
    if (stalled >= 2) break;
    previous = out.residual;
  }
  require_resolved(c, n);
  derivatives_at_start(q0, v0, tau, c, out.derivs);
  return out;
}

int start(Integrator& integrator, System& system, double t0, double dt, std::span<const double> q0,
          std::span<const double> v0, StartKind start, double tau) {
  auto* gear = dynamic_cast<Gear5*>(&integrator);
  if (start == StartKind::zero || gear == nullptr) {
    integrator.start(system, t0, dt, q0, v0);
    return 0;
  }
  const TaylorStart ts = taylor_derivatives(system, t0, q0, v0, tau);
  gear->start_exact(system, t0, dt, ts.derivs);
  return ts.evaluations;
}

void Integrator::declare_clock(StateRegistry& registry) {
  registry.other([this](StateArchive& a) {
    StateArchive::Scope scope(a, "integrator");
    a.value("t", t_);
    a.value("steps", steps_);
  });
}

void Integrator::visit_state(StateArchive& archive) {
  StateRegistry registry(n_ / blocks_);
  declare_state(registry);
  registry.visit(archive);
}

void System::bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  bound_t_ = t;
  bound_q_ = q;
  bound_v_ = v;
  bound_a_ = a;
}

Phases System::force_phases() {
  Phases p;
  p.add({"accelerations",
         true,
         [this](std::size_t, std::size_t) { accelerations(bound_t_, bound_q_, bound_v_, bound_a_); },
         {}});
  return p;
}

void Integrator::step(System& system) {
  if (step_system_ != &system) {
    step_ = step_phases(system);
    step_system_ = &system;
  }
  begin_step(system);
  step_.run(team_for(system));
}

Phase Integrator::clock_phase(const TeamSlots<int>& bad) {
  return {"step: clock",
          true,
          [this, &bad](std::size_t, std::size_t nt) {
            int any = 0;
            for (std::size_t t = 0; t < nt; ++t) any |= bad[t];
            finite_ = any == 0;
            t_ += dt_;
            ++steps_;
          },
          {}};
}

// ---------------------------------------------------------------- Gear5
namespace {
constexpr double kGearC[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
}

void Gear5::start(System& system, double t0, double dt, std::span<const double> q0, std::span<const double> v0) {
  step_system_ = nullptr;
  n_ = q0.size();
  blocks_ = system.coordinate_blocks();
  t_ = t0;
  dt_ = dt;
  steps_ = 0;
  layout_ = PartLayout(n_, blocks_, team_for(system));
  r_[0].assign(q0.begin(), q0.end());
  for (int k = 1; k < 6; ++k) r_[k].assign(layout_.size(), 0.0);
  v_.assign(v0.begin(), v0.end());
  a_.assign(n_, 0.0);
  system.prescribe(t_, r_[0], v_, a_);
  system.accelerations(t_, r_[0], v_, a_);
  system.prescribe(t_, r_[0], v_, a_);
  for (std::size_t i = 0; i < n_; ++i) {
    r(1, i) = dt * v_[i];
    r(2, i) = 0.5 * dt * dt * a_[i];
  }
}

void Gear5::start_exact(System& system, double t0, double dt, const std::vector<std::vector<double>>& derivs) {
  start(system, t0, dt, derivs.at(0), derivs.at(1));
  double scale = dt * dt / 2;
  for (int k = 3; k <= 5; ++k) {
    scale *= dt / k;
    for (std::size_t i = 0; i < n_; ++i) r(k, i) = scale * derivs.at(static_cast<std::size_t>(k))[i];
  }
}

void Gear5::set_velocity(std::size_t i, double value) {
  v_[i] = value;
  r(1, i) = dt_ * value;
}

void Gear5::declare_state(StateRegistry& registry) {
  declare_clock(registry);
  registry.cell_field({"integrator/q", &r_[0], blocks_, nullptr});
  registry.cell_field({"integrator/v", &v_, blocks_, nullptr});
  registry.cell_field({"integrator/a", &a_, blocks_, nullptr});
  // r1..r5 saved in the system's order (the layout of the threads' parts depends on the thread count).
  for (int k = 1; k < 6; ++k) registry.cell_field({"integrator/r" + std::to_string(k), &r_[k], blocks_, &layout_});
}

void Gear5::apply_prescribed(const System& system, double t) {
  const auto fixed = system.prescribed();
  if (fixed.empty()) return;
  system.prescribe(t, r_[0], v_, a_);
  for (std::size_t i : fixed) {
    r(1, i) = dt_ * v_[i];
    r(2, i) = 0.5 * dt_ * dt_ * a_[i];
    r(3, i) = r(4, i) = r(5, i) = 0.0;
  }
}

// Gear's predictor and corrector (declared in integrator.hpp). The arrays do not overlap (restrict), and each
// value is read once into a local, so no store forces a reload and the loops vectorise.
// Predictor: Pascal's triangle, each line reading only not-yet-updated higher orders; v = r1/dt.
void gear5_predict(std::size_t first, std::size_t last, double* __restrict r0, double* __restrict r1,
                   double* __restrict r2, double* __restrict r3, double* __restrict r4, const double* __restrict r5,
                   double* __restrict v, double inv_dt) {
#pragma omp simd
  for (std::size_t i = first; i < last; ++i) {
    const double d1 = r1[i], d2 = r2[i], d3 = r3[i], d4 = r4[i], d5 = r5[i];
    r0[i] += d1 + d2 + d3 + d4 + d5;
    const double n1 = d1 + (2 * d2 + 3 * d3 + 4 * d4 + 5 * d5);
    r1[i] = n1;
    r2[i] = d2 + (3 * d3 + 6 * d4 + 10 * d5);
    r3[i] = d3 + (4 * d4 + 10 * d5);
    r4[i] = d4 + 5 * d5;
    v[i] = n1 * inv_dt;
  }
}

// Corrector, from the accelerations a at the predicted state; returns whether a corrected q or v is not
// finite (core/finite.hpp).
int gear5_correct(std::size_t first, std::size_t last, double* __restrict r0, double* __restrict r1,
                  double* __restrict r2, double* __restrict r3, double* __restrict r4, double* __restrict r5,
                  double* __restrict v, const double* __restrict a, double half_dt2, double inv_dt) {
  std::uint64_t bad = 0;
#pragma omp simd reduction(| : bad)
  for (std::size_t i = first; i < last; ++i) {
    const double delta = half_dt2 * a[i] - r2[i];
    const double n0 = r0[i] + kGearC[0] * delta, n1 = r1[i] + kGearC[1] * delta;
    r0[i] = n0;
    r1[i] = n1;
    r2[i] += kGearC[2] * delta;
    r3[i] += kGearC[3] * delta;
    r4[i] += kGearC[4] * delta;
    r5[i] += kGearC[5] * delta;
    const double vi = n1 * inv_dt;
    v[i] = vi;
    bad |= non_finite_bit(n0) | non_finite_bit(vi);
  }
  return non_finite_seen(bad) ? 1 : 0;
}

void Gear5::begin_step(System& system) {
  bad_.reserve(team_for(system));
  system.bind(t_ + dt_, r_[0], v_, a_);
}

Phases Gear5::step_phases(System& system, const Phases& after) {
  // Each loop on the threads' parts of the coordinates (PartLayout: r_[1..5] shifted), split as the system splits
  // its cells.
  Phases p;
  p.add({"predict",
         false,
         [this](std::size_t, std::size_t) {
           double *r1 = r_[1].data(), *r2 = r_[2].data(), *r3 = r_[3].data(), *r4 = r_[4].data();
           const double* r5 = r_[5].data();
           layout_.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t s) {
             gear5_predict(first, last, r_[0].data(), r1 + s, r2 + s, r3 + s, r4 + s, r5 + s, v_.data(), 1.0 / dt_);
           });
         },
         {}});
  const auto prescribed = [&system] { return !system.prescribed().empty(); };
  p.add({"prescribe", true, [this, &system](std::size_t, std::size_t) { apply_prescribed(system, t_ + dt_); },
         prescribed});
  p.add(system.force_phases());
  p.add({"correct",
         false,
         [this](std::size_t t, std::size_t) {
           double *r1 = r_[1].data(), *r2 = r_[2].data(), *r3 = r_[3].data(), *r4 = r_[4].data(), *r5 = r_[5].data();
           int bad = 0;
           layout_.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t s) {
             bad |= gear5_correct(first, last, r_[0].data(), r1 + s, r2 + s, r3 + s, r4 + s, r5 + s, v_.data(),
                                  a_.data(), 0.5 * dt_ * dt_, 1.0 / dt_);
           });
           bad_[t] = bad;
         },
         {}});
  p.add({"prescribe", true, [this, &system](std::size_t, std::size_t) { apply_prescribed(system, t_ + dt_); },
         prescribed});
  p.add(clock_phase(bad_));
  p.add(after);
  return p;
}

// ---------------------------------------------------------------- velocity Verlet
void VelocityVerlet::declare_state(StateRegistry& registry) {
  declare_clock(registry);
  registry.cell_field({"integrator/q", &q_, blocks_, nullptr});
  registry.cell_field({"integrator/v", &v_, blocks_, nullptr});
  registry.cell_field({"integrator/a", &a_, blocks_, nullptr});
}

void VelocityVerlet::start(System& system, double t0, double dt, std::span<const double> q0,
                           std::span<const double> v0) {
  step_system_ = nullptr;
  n_ = q0.size();
  blocks_ = system.coordinate_blocks();
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

void VelocityVerlet::begin_step(System& system) {
  bad_.reserve(team_for(system));
  system.bind(t_ + dt_, q_, v_est_, a_);
}

Phases VelocityVerlet::step_phases(System& system, const Phases& after) {
  const std::size_t blocks = system.coordinate_blocks();
  Phases p;
  p.add({"kick and drift",
         false,
         [this, blocks](std::size_t t, std::size_t nt) {
           const double h = 0.5 * dt_, dt = dt_;
           double *q = q_.data(), *v = v_.data(), *v_est = v_est_.data();
           const double* a = a_.data();
           coordinate_ranges(n_, blocks, t, nt, [&](std::size_t first, std::size_t last) {
#pragma omp simd
             for (std::size_t i = first; i < last; ++i) {
               v[i] += h * a[i];            // half kick
               q[i] += dt * v[i];           // drift
               v_est[i] = v[i] + h * a[i];  // velocity estimate at the new time for velocity-dependent forces
             }
           });
         },
         {}});
  p.add({"prescribe",
         true,
         [this, &system](std::size_t, std::size_t) { system.prescribe(t_ + dt_, q_, v_est_, a_); },
         {}});
  p.add(system.force_phases());
  p.add({"kick",
         false,
         [this, blocks](std::size_t t, std::size_t nt) {
           const double h = 0.5 * dt_;
           const double *q = q_.data(), *a = a_.data();
           double* v = v_.data();
           std::uint64_t bad = 0;
           coordinate_ranges(n_, blocks, t, nt, [&](std::size_t first, std::size_t last) {
#pragma omp simd reduction(| : bad)
             for (std::size_t i = first; i < last; ++i) {
               v[i] += h * a[i];  // half kick
               bad |= non_finite_bit(q[i]) | non_finite_bit(v[i]);
             }
           });
           bad_[t] = non_finite_seen(bad) ? 1 : 0;
         },
         {}});
  p.add({"prescribe", true, [this, &system](std::size_t, std::size_t) { system.prescribe(t_ + dt_, q_, v_, a_); },
         [&system] { return !system.prescribed().empty(); }});
  p.add(clock_phase(bad_));
  p.add(after);
  return p;
}

}  // namespace frac::dynamics
