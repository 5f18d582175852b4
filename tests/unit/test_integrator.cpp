// The shared time integrators (lib/dynamics/integrator): stability limits and convergence orders,
// measured on oscillators with exact solutions (physics/polygon-dem.md §6, validation table E9).
//
// Stability. Run 10^5 steps of ẍ = −ω²x at ω·dt = h and measure the growth rate of the amplitude per
// step, r = ln(E_B/E_A)/(2·8e4), with E_A, E_B the largest oscillator energy ½(v² + ω²x²) over steps
// [1e4, 2e4) and [9e4, 1e5): r ≈ |λ| − 1 of the dominant eigenvalue of the step. The scheme counts as
// stable when r ≤ 1e-8 (an amplitude growth of at most e^0.01 over 10^6 steps, i.e. over any DEM run).
// The threshold sits far above the noise of the window maxima (the energy is sampled at every phase of
// an irrational period; ~1e-9 relative, i.e. r ~ 1e-14) and far below the growth of a clearly unstable
// scheme. A looser criterion (e.g. "the energy does not double over 10^5 steps") accepts the weak
// instability of gear5 above ω·dt ≈ 0.313, where |λ| − 1 is only 4e-7 (at 0.32) to 6e-6 (at 0.36):
// slow, but it compounds (a factor 170 in amplitude over 10^6 steps at 0.356, see
// Gear5LongRunJustBelowItsStatedLimit). The edge 0.3130 agrees with the spectral radius of gear5's 6×6
// step matrix on this oscillator, computed independently when this test was written (|λ| = 1 at
// ω·dt = 0.31297).
//
// Convergence. The error is the largest |x − x_exact| + |v − v_exact|/ω over 20 common sample times
// in [0, T]; the observed order is the least-squares slope of log(error) against log(dt) over four
// halvings of dt. Bands: the leading error term dominates only asymptotically, and the next term is
// one power of ω·dt smaller; at the largest ω·dt used (0.2 for gear5, 0.1 for Verlet) that biases a
// single halving by at most ~0.3 in the order, less for the fit. So Verlet must give 2 ± 0.2, gear5
// with exact initial derivatives 5 ± 0.5. With the usual start (r3 = r4 = r5 = 0) gear5 converges
// only at O(dt²) (the start error); we require the order to be below 3 to show that it is not 5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "dynamics/integrator.hpp"

namespace {

using frac::dynamics::Gear5;
using frac::dynamics::Integrator;
using frac::dynamics::IntegratorKind;
using frac::dynamics::System;
using frac::dynamics::VelocityVerlet;

// ẍ = −ω² x − γ ẋ, one coordinate.
class Oscillator final : public System {
 public:
  Oscillator(double omega, double gamma) : w2_(omega * omega), gamma_(gamma) {}
  void accelerations(double, std::span<const double> q, std::span<const double> v, std::span<double> a) override {
    a[0] = -w2_ * q[0] - gamma_ * v[0];
  }

 private:
  double w2_, gamma_;
};

// Exact solution from x(0) = x0 = cos 1, v(0) = v0 = −sin 1 (a phase at which every derivative is
// nonzero, so that no start error vanishes by accident), underdamped:
// x = e^{−kt}(A cos ω_d t + B sin ω_d t), k = γ/2, A = x0, B = (v0 + k x0)/ω_d.
struct Exact {
  double omega, gamma;
  double x0 = std::cos(1.0), v0 = -std::sin(1.0);
  double wd() const { return std::sqrt(omega * omega - 0.25 * gamma * gamma); }
  double b() const { return (v0 + 0.5 * gamma * x0) / wd(); }
  double x(double t) const {
    const double k = 0.5 * gamma, w = wd();
    return std::exp(-k * t) * (x0 * std::cos(w * t) + b() * std::sin(w * t));
  }
  double v(double t) const {
    const double k = 0.5 * gamma, w = wd(), a = x0, bb = b();
    return std::exp(-k * t) * ((-k * a + w * bb) * std::cos(w * t) + (-k * bb - w * a) * std::sin(w * t));
  }
  // d^k x/dt^k at t = 0 for k = 0..5, from x^(k+2) = −ω² x^(k) − γ x^(k+1).
  std::vector<std::vector<double>> derivatives() const {
    std::vector<double> d(6);
    d[0] = x0;
    d[1] = v0;
    for (int k = 2; k < 6; ++k) d[k] = -omega * omega * d[k - 2] - gamma * d[k - 1];
    std::vector<std::vector<double>> out;
    for (double x : d) out.push_back({x});
    return out;
  }
};

// How a run starts: the usual start, gear5 from the exact derivatives of Exact, or gear5 from the
// derivatives the library computes from the equations of motion (dynamics::taylor_derivatives, what
// dem-run's integrator.start = exact uses), with tau = 0.1/ω.
enum class Start { usual, exact, taylor };

// Largest error against the exact solution over 20 sample times in (0, T].
double run_error(Integrator& in, Oscillator& sys, const Exact& ex, double T, int steps, Start start) {
  const double dt = T / steps;
  if (start == Start::exact) {
    dynamic_cast<Gear5&>(in).start_exact(sys, 0.0, dt, ex.derivatives());
  } else if (start == Start::taylor) {
    const std::vector<double> q0{ex.x0}, v0{ex.v0};
    frac::dynamics::start(in, sys, 0.0, dt, q0, v0, frac::dynamics::StartKind::exact, 0.1 / ex.omega);
  } else {
    const std::vector<double> q0{ex.x0}, v0{ex.v0};
    in.start(sys, 0.0, dt, q0, v0);
  }
  double err = 0;
  const int every = steps / 20;
  for (int s = 1; s <= steps; ++s) {
    in.step(sys);
    if (s % every == 0) {
      const double t = s * dt;
      err = std::max(err, std::abs(in.q()[0] - ex.x(t)) + std::abs(in.v()[0] - ex.v(t)) / ex.omega);
    }
  }
  return err;
}

// Least-squares slope of log(err) against log(dt).
double order(const std::vector<double>& dts, const std::vector<double>& errs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(dts.size());
  for (std::size_t k = 0; k < dts.size(); ++k) {
    const double x = std::log(dts[k]), y = std::log(errs[k]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

struct Convergence {
  std::vector<double> dt, err;
  double p;
};

Convergence measure(Integrator& in, double gamma, double T, int steps0, Start start) {
  const Exact ex{1.0, gamma};
  Oscillator sys(ex.omega, ex.gamma);
  Convergence c;
  for (int k = 0; k < 5; ++k) {
    const int steps = steps0 << k;
    c.dt.push_back(T / steps);
    c.err.push_back(run_error(in, sys, ex, T, steps, start));
  }
  c.p = order(c.dt, c.err);
  return c;
}

void print(const char* what, const Convergence& c) {
  std::printf("[ order    ] %-44s", what);
  for (std::size_t k = 0; k < c.dt.size(); ++k) std::printf(" dt=%.4g:%.3e", c.dt[k], c.err[k]);
  std::printf("  -> observed order %.3f\n", c.p);
}

// Growth rate per step of the oscillator amplitude at ω·dt = h (ω = 1), as described in the header;
// infinity if anything became non-finite.
double growth_rate(IntegratorKind kind, double h, int n = 100000) {
  Oscillator sys(1.0, 0.0);
  auto in = frac::dynamics::make_integrator(kind);
  const std::vector<double> q0{1.0}, v0{0.0};
  in->start(sys, 0.0, h, q0, v0);
  double ea = 0, eb = 0;
  for (int s = 1; s <= n; ++s) {
    in->step(sys);
    const double x = in->q()[0], v = in->v()[0];
    const double e = 0.5 * (v * v + x * x);
    if (!std::isfinite(e)) return INFINITY;
    if (s >= n / 10 && s < n / 5) ea = std::max(ea, e);
    if (s >= n - n / 10) eb = std::max(eb, e);
  }
  return std::log(eb / ea) / (2.0 * (n - n / 10 - n / 10));
}

bool stable(IntegratorKind kind, double h) { return growth_rate(kind, h) <= 1e-8; }

// Edge of stability by bisection in [lo, hi] (lo stable, hi unstable), to 1e-4 relative.
double measured_limit(IntegratorKind kind, double lo, double hi) {
  EXPECT_TRUE(stable(kind, lo));
  EXPECT_FALSE(stable(kind, hi));
  while (hi - lo > 1e-4 * lo) {
    const double mid = 0.5 * (lo + hi);
    (stable(kind, mid) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(Integrator, ParseKind) {
  EXPECT_EQ(frac::dynamics::parse_integrator_kind("gear5", "k"), IntegratorKind::gear5);
  EXPECT_EQ(frac::dynamics::parse_integrator_kind("verlet", "k"), IntegratorKind::verlet);
  try {
    frac::dynamics::parse_integrator_kind("rk4", "integrator.kind");
    FAIL() << "rk4 accepted";
  } catch (const frac::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("integrator.kind"), std::string::npos) << e.what();
  }
}

// The time-step check divides stability_limit(kind) by ω_max, so the constant must be on the stable
// side of the true edge and not far from it. "Just below" = 0.99 of the constant; "somewhat above" =
// 1.05 of it (for Verlet the edge ω·dt = 2 is exact; 1.01 of it already grows fast). The constant must
// also not waste more than 5% of the usable step.
TEST(Integrator, Gear5StabilityLimit) {
  const double limit = frac::dynamics::stability_limit(IntegratorKind::gear5);
  const double measured = measured_limit(IntegratorKind::gear5, 0.5 * limit, 2.0 * limit);
  std::printf(
      "[ stability] gear5: stability_limit = %.4f, measured edge = %.4f; amplitude growth rate per step at "
      "0.95 edge %.2e, 0.99 limit %.2e, 1.05 limit %.2e\n",
      limit, measured, growth_rate(IntegratorKind::gear5, 0.95 * measured),
      growth_rate(IntegratorKind::gear5, 0.99 * limit), growth_rate(IntegratorKind::gear5, 1.05 * limit));
  EXPECT_TRUE(stable(IntegratorKind::gear5, 0.99 * limit))
      << "gear5 is unstable just below its stated limit: |λ| − 1 = " << growth_rate(IntegratorKind::gear5, 0.99 * limit)
      << " per step at ω·dt = " << 0.99 * limit << "; the measured edge is " << measured;
  EXPECT_FALSE(stable(IntegratorKind::gear5, 1.05 * limit)) << "gear5 still stable well above its stated limit";
  EXPECT_LE(limit, measured);
  EXPECT_GE(limit, 0.95 * measured);
}

// What the weak instability does over a long run: the amplitude after 10^6 steps from x = 1 at rest,
// at 0.99 of the stated limit. A stable scheme keeps it at or below 1 (gear5 is slightly dissipative).
TEST(Integrator, Gear5LongRunJustBelowItsStatedLimit) {
  const double h = 0.99 * frac::dynamics::stability_limit(IntegratorKind::gear5);
  Oscillator sys(1.0, 0.0);
  Gear5 g;
  const std::vector<double> q0{1.0}, v0{0.0};
  g.start(sys, 0.0, h, q0, v0);
  double amplitude = 0;
  for (int s = 1; s <= 1000000; ++s) {
    g.step(sys);
    if (s > 990000) amplitude = std::max(amplitude, std::hypot(g.q()[0], g.v()[0]));
  }
  std::printf("[ stability] gear5 at omega dt = %.4f: amplitude after 1e6 steps = %.4g (started at 1)\n", h, amplitude);
  EXPECT_LE(amplitude, 1.01);
}

TEST(Integrator, VerletStabilityLimit) {
  const double limit = frac::dynamics::stability_limit(IntegratorKind::verlet);
  EXPECT_EQ(limit, 2.0);
  const double measured = measured_limit(IntegratorKind::verlet, 1.0, 2.5);
  std::printf("[ stability] verlet: stability_limit = %.4f, measured edge = %.5f\n", limit, measured);
  EXPECT_TRUE(stable(IntegratorKind::verlet, 0.99 * limit));
  EXPECT_FALSE(stable(IntegratorKind::verlet, 1.01 * limit));
  EXPECT_NEAR(measured, 2.0, 2e-3);
}

// Velocity-dependent forces (damping, friction): the stability edge in γ·dt of ẍ = −γẋ, i.e. of the
// velocity decaying at the rate γ. No constant in the library states it, but the time-step check has to
// respect it whenever damping or friction is on. Velocity Verlet (forces at v + dt·a_old): the step
// matrix on (v, a) has trace 1 − 1.5 γdt and determinant −γdt/2, so it is stable exactly for γdt < 1.
// Gear5 with c0 = 3/16: the eigenvalues of its 6×6 step matrix cross the unit circle at γdt = 0.1633
// (computed independently when this test was written), six times below Verlet's edge. Measured here as
// above (growth rate of |v| ≤ 1e-8 per step, with ω = 0): Verlet within 1% of 1, gear5 within 2% of
// 0.1633. test_dem_model (AutoTimeStepIsStableWithDampingAndFriction) shows what this means for the DEM.
double damping_growth_rate(IntegratorKind kind, double gdt, int n = 20000) {
  Oscillator sys(0.0, gdt);  // dt = 1, γ = gdt
  auto in = frac::dynamics::make_integrator(kind);
  const std::vector<double> q0{0.0}, v0{1.0};
  in->start(sys, 0.0, 1.0, q0, v0);
  // Below the edge the velocity decays; once it reaches 1e-100 it is held at that floor (with an
  // alternating sign, which excites every mode), so the late and early maxima are equal and the rate is
  // ~0. Above the edge the fastest-growing mode wins and the rate is its ln|λ|.
  double ea = 0, eb = 0;
  for (int s = 1; s <= n; ++s) {
    in->step(sys);
    const double v = std::abs(in->v()[0]);
    if (!std::isfinite(v) || v > 1e200) return INFINITY;
    if (s >= n / 10 && s < n / 5) ea = std::max(ea, v);
    if (s >= n - n / 10) eb = std::max(eb, v);
    if (v < 1e-100) in->set_velocity(0, 1e-100 * (s % 2 ? 1 : -1));
  }
  return std::log(eb / ea) / (n - n / 10 - n / 10);
}

double damping_edge(IntegratorKind kind, double lo, double hi) {
  auto unstable = [&](double g) { return damping_growth_rate(kind, g) > 1e-8; };
  EXPECT_FALSE(unstable(lo));
  EXPECT_TRUE(unstable(hi));
  while (hi - lo > 1e-4 * lo) {
    const double mid = 0.5 * (lo + hi);
    (unstable(mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(Integrator, DampingStabilityEdges) {
  const double verlet = damping_edge(IntegratorKind::verlet, 0.5, 1.5);
  const double gear = damping_edge(IntegratorKind::gear5, 0.05, 0.5);
  std::printf("[ stability] pure damping x'' = -gamma x': edge gamma dt = %.4f (verlet), %.4f (gear5, c0 = 3/16)\n",
              verlet, gear);
  EXPECT_NEAR(verlet, 1.0, 0.01);
  EXPECT_NEAR(gear, 0.1633, 0.02 * 0.1633);
}

// T = 2π·3 (three periods), 100·2^k steps: gear5 from ω·dt = 0.19 down to 0.012 (Verlet from 0.094), sampled
// at the 20 common times jT/20; errors from ~1e-5 to ~1e-11, all far
// above the accumulated round-off (~1e-13 after 1.5e3 steps).
TEST(Integrator, Gear5ExactStartIsFifthOrderOnHarmonicOscillator) {
  Gear5 g;
  const double T = 6 * std::numbers::pi;
  const auto c = measure(g, 0.0, T, 100, Start::exact);
  print("gear5, exact start, harmonic", c);
  EXPECT_NEAR(c.p, 5.0, 0.5);
}

TEST(Integrator, Gear5ExactStartOnDampedOscillator) {
  Gear5 g;
  const double T = 6 * std::numbers::pi;
  const auto c = measure(g, 0.2, T, 100, Start::exact);
  print("gear5, exact start, damped (gamma = 0.2 omega)", c);
  // Velocity-dependent force: the note measures 5.0 here too (validation E9).
  EXPECT_NEAR(c.p, 5.0, 0.5);
}

TEST(Integrator, Gear5UsualStartIsOnlySecondOrder) {
  Gear5 g;
  const double T = 6 * std::numbers::pi;
  const auto c = measure(g, 0.0, T, 100, Start::usual);
  print("gear5, usual start (r3..r5 = 0), harmonic", c);
  EXPECT_LT(c.p, 3.0);
  EXPECT_GT(c.p, 1.5);
}

// The exact start from the equations of motion alone (dynamics::taylor_derivatives): its derivatives
// agree with the analytic ones (ω = 1: q'' .. q'''' to 1e-12, q^(5) to 1e-10; damped, so that the velocity
// dependence enters too), and gear5 started from them converges at order 5 like the analytic start.
TEST(Integrator, TaylorDerivativesFromTheEquationsOfMotion) {
  const Exact ex{1.0, 0.2};
  Oscillator sys(ex.omega, ex.gamma);
  const std::vector<double> q0{ex.x0}, v0{ex.v0};
  const auto ts = frac::dynamics::taylor_derivatives(sys, 0.0, q0, v0, 0.1 / ex.omega);
  const auto want = ex.derivatives();
  ASSERT_EQ(ts.derivs.size(), 6u);
  // The rounding of the accelerations (1e-16) is amplified by 1/tau^(k-2) in the k-th derivative.
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_NEAR(ts.derivs[k][0], want[k][0], k < 5 ? 1e-12 : 1e-10) << "derivative " << k;
  std::printf("[ taylor   ] %d Picard passes, %d force evaluations, residual %.2g\n", ts.iterations, ts.evaluations,
              ts.residual);
  EXPECT_LE(ts.evaluations, 150);
  // A tau far beyond the fastest motion makes the iteration diverge: refused, not silently wrong.
  EXPECT_THROW(frac::dynamics::taylor_derivatives(sys, 0.0, q0, v0, 10.0 / ex.omega), frac::RuntimeError);
}

TEST(Integrator, Gear5TaylorStartIsFifthOrder) {
  Gear5 g;
  const double T = 6 * std::numbers::pi;
  const auto h = measure(g, 0.0, T, 100, Start::taylor);
  print("gear5, start from taylor_derivatives, harmonic", h);
  EXPECT_NEAR(h.p, 5.0, 0.5);
  const auto d = measure(g, 0.2, T, 100, Start::taylor);
  print("gear5, start from taylor_derivatives, damped", d);
  EXPECT_NEAR(d.p, 5.0, 0.5);
  // Verlet carries no higher derivatives: an exact start is its usual start.
  VelocityVerlet a, b;
  Oscillator sys(1.0, 0.0);
  const std::vector<double> q0{1.0}, v0{0.5};
  EXPECT_EQ(frac::dynamics::start(a, sys, 0.0, 0.1, q0, v0, frac::dynamics::StartKind::exact, 0.1), 0);
  b.start(sys, 0.0, 0.1, q0, v0);
  for (int s = 0; s < 10; ++s) {
    a.step(sys);
    b.step(sys);
  }
  EXPECT_EQ(a.q()[0], b.q()[0]);
}

TEST(Integrator, ParseStartKind) {
  EXPECT_EQ(frac::dynamics::parse_start_kind("zero", "k"), frac::dynamics::StartKind::zero);
  EXPECT_EQ(frac::dynamics::parse_start_kind("exact", "k"), frac::dynamics::StartKind::exact);
  EXPECT_THROW(frac::dynamics::parse_start_kind("taylor", "integrator.start"), frac::UsageError);
  EXPECT_EQ(frac::dynamics::name(frac::dynamics::StartKind::exact), "exact");
}

TEST(Integrator, VerletIsSecondOrder) {
  VelocityVerlet vv;
  const double T = 6 * std::numbers::pi;
  const auto h = measure(vv, 0.0, T, 200, Start::usual);
  print("verlet, harmonic", h);
  EXPECT_NEAR(h.p, 2.0, 0.2);
  const auto d = measure(vv, 0.2, T, 200, Start::usual);
  print("verlet, damped (gamma = 0.2 omega)", d);
  EXPECT_NEAR(d.p, 2.0, 0.2);
}

// Prescribed coordinates are overwritten, never integrated: a coordinate driven at x(t) = t² follows
// it exactly (to round-off) with both schemes, while a free one still integrates.
class Driven final : public System {
 public:
  void accelerations(double, std::span<const double> q, std::span<const double>, std::span<double> a) override {
    a[0] = -q[0];
    a[1] = 1e6;  // whatever the force, the prescribed coordinate must ignore it
  }
  std::span<const std::size_t> prescribed() const override { return index_; }
  void prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const override {
    q[1] = t * t;
    v[1] = 2 * t;
    a[1] = 2;
  }

 private:
  std::size_t index_[1] = {1};
};

TEST(Integrator, PrescribedCoordinatesFollowTheirTrajectory) {
  for (IntegratorKind kind : {IntegratorKind::gear5, IntegratorKind::verlet}) {
    Driven sys;
    auto in = frac::dynamics::make_integrator(kind);
    const std::vector<double> q0{1.0, 0.0}, v0{0.0, 0.0};
    const double dt = 1e-2;
    in->start(sys, 0.0, dt, q0, v0);
    for (int s = 0; s < 1000; ++s) in->step(sys);
    const double t = in->t();
    EXPECT_NEAR(t, 10.0, 1e-12);
    EXPECT_DOUBLE_EQ(in->q()[1], t * t);
    EXPECT_DOUBLE_EQ(in->v()[1], 2 * t);
    // The free coordinate: cos t to the scheme's accuracy (Verlet: ~(dt²/24)·t ≈ 4e-5).
    EXPECT_NEAR(in->q()[0], std::cos(t), 1e-4) << frac::dynamics::name(kind);
  }
}

// Gear5's loops (vectorised, restrict pointers, each value read once) against the scheme written out as the
// physics note gives it (predictor, prescribed coordinates, forces at the predicted state, corrector,
// prescribed again): the same bits at every step, on a nonlinear system with velocity-dependent forces and a
// prescribed coordinate, on the threads' loops, with kicks between steps (set_velocity: r1 = dt·v).
class NonlinearDriven final : public System {
 public:
  explicit NonlinearDriven(std::size_t n) : index_{n - 2} {}
  void accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override {
    for (std::size_t i = 0; i < q.size(); ++i)
      a[i] =
          -q[i] * (1 + 0.3 * q[i] * q[i]) - 0.05 * v[i] * std::abs(v[i]) + 0.1 * std::sin(t + static_cast<double>(i));
  }
  std::span<const std::size_t> prescribed() const override { return index_; }
  void prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const override {
    q[index_[0]] = std::sin(3 * t);
    v[index_[0]] = 3 * std::cos(3 * t);
    a[index_[0]] = -9 * std::sin(3 * t);
  }
  std::size_t coordinate_blocks() const override { return 3; }

 private:
  std::size_t index_[1];
};

struct ReferenceGear5 {
  std::vector<double> r[6], v, a;
  double t = 0, dt = 0;
  void prescribed(NonlinearDriven& sys, bool derivatives) {
    sys.prescribe(t, r[0], v, a);
    if (!derivatives) return;
    for (std::size_t i : sys.prescribed()) {
      r[1][i] = dt * v[i];
      r[2][i] = 0.5 * dt * dt * a[i];
      r[3][i] = r[4][i] = r[5][i] = 0.0;
    }
  }
  void start(NonlinearDriven& sys, double step, const std::vector<double>& q0, const std::vector<double>& v0) {
    dt = step;
    for (auto& x : r) x.assign(q0.size(), 0.0);
    r[0] = q0;
    v = v0;
    a.assign(q0.size(), 0.0);
    prescribed(sys, false);
    sys.accelerations(t, r[0], v, a);
    prescribed(sys, false);
    for (std::size_t i = 0; i < v.size(); ++i) {
      r[1][i] = dt * v[i];
      r[2][i] = 0.5 * dt * dt * a[i];
    }
  }
  void step(NonlinearDriven& sys) {
    constexpr double c[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
    const double inv_dt = 1.0 / dt, half_dt2 = 0.5 * dt * dt;
    for (std::size_t i = 0; i < v.size(); ++i) {
      r[0][i] += r[1][i] + r[2][i] + r[3][i] + r[4][i] + r[5][i];
      r[1][i] += 2 * r[2][i] + 3 * r[3][i] + 4 * r[4][i] + 5 * r[5][i];
      r[2][i] += 3 * r[3][i] + 6 * r[4][i] + 10 * r[5][i];
      r[3][i] += 4 * r[4][i] + 10 * r[5][i];
      r[4][i] += 5 * r[5][i];
      v[i] = r[1][i] * inv_dt;
    }
    t += dt;
    prescribed(sys, true);
    sys.accelerations(t, r[0], v, a);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double delta = half_dt2 * a[i] - r[2][i];
      for (int k = 0; k < 6; ++k) r[k][i] += c[k] * delta;
      v[i] = r[1][i] * inv_dt;
    }
    prescribed(sys, true);
  }
};

TEST(Integrator, Gear5IsThePredictorCorrectorSchemeBitForBit) {
#ifdef FRACTURE_NATIVE_BUILD
  GTEST_SKIP() << "native build: FMA contraction makes other bits than the reference's";
#endif
  const std::size_t n = 3 * (frac::kMinParallelCoordinates / 3 + 50);  // on the threads
  std::vector<double> q0(n), v0(n);
  for (std::size_t i = 0; i < n; ++i) {
    q0[i] = std::sin(0.37 * static_cast<double>(i));
    v0[i] = std::cos(0.11 * static_cast<double>(i));
  }
  NonlinearDriven sys(n);
  ReferenceGear5 ref;
  ref.start(sys, 1e-2, q0, v0);
  auto gear = frac::dynamics::make_integrator(IntegratorKind::gear5);
  gear->start(sys, 0.0, 1e-2, q0, v0);
  for (int s = 1; s <= 300; ++s) {
    ref.step(sys);
    gear->step(sys);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(gear->q()[i], ref.r[0][i]) << "step " << s << ", coordinate " << i;
      ASSERT_EQ(gear->v()[i], ref.v[i]) << "step " << s << ", coordinate " << i;
      ASSERT_EQ(gear->a()[i], ref.a[i]) << "step " << s << ", coordinate " << i;
    }
    if (s % 100 == 50) {  // a kick between steps
      gear->set_velocity(7, 2.5);
      ref.v[7] = 2.5;
      ref.r[1][7] = ref.dt * 2.5;
    }
  }
}

}  // namespace

// finite() says whether the last step left q and v finite: ẍ = +ω²x (unstable) on enough coordinates to
// run the threaded loops, with one coordinate far ahead of the rest, overflows after some hundreds of
// steps; finite() must hold while every value is finite and turn false at the step that makes one infinite
// or NaN, for both schemes.
class Runaway final : public System {
 public:
  void accelerations(double, std::span<const double> q, std::span<const double>, std::span<double> a) override {
    for (std::size_t i = 0; i < q.size(); ++i) a[i] = q[i];
  }
  std::size_t coordinate_blocks() const override { return 3; }
};

TEST(Integrator, FiniteTellsWhenTheStateOverflows) {
  for (const auto kind : {IntegratorKind::gear5, IntegratorKind::verlet}) {
    const std::size_t n = 3 * (frac::kMinParallelCoordinates / 3 + 100);  // on the threads
    std::vector<double> q0(n, 1e-3), v0(n, 0.0);
    q0[n - 7] = 1e300;  // the one that overflows first, in the last thread's part
    Runaway sys;
    auto integrator = frac::dynamics::make_integrator(kind);
    integrator->start(sys, 0.0, 0.5, q0, v0);
    int steps = 0;
    bool all_finite = true;
    while (all_finite && steps < 10000) {
      integrator->step(sys);
      ++steps;
      all_finite = true;
      for (std::size_t i = 0; i < n; ++i)
        all_finite &= std::isfinite(integrator->q()[i]) && std::isfinite(integrator->v()[i]);
      ASSERT_EQ(integrator->finite(), all_finite) << name(kind) << " at step " << steps;
    }
    EXPECT_FALSE(all_finite) << name(kind) << ": never overflowed";
    EXPECT_GT(steps, 1) << name(kind);
  }
}
