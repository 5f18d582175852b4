#pragma once
// Time integrators shared by both models (polygon DEM and rubber lattice), over flat coordinate arrays.
// A model exposes itself as a System: n generalised coordinates q (for the DEM: x of every cell, then y,
// then the angle φ; for the rubber lattice: x then y of every node), whose accelerations depend on q,
// the velocities v and the time. Two schemes sit behind one interface:
//   gear5  : Gear's 6-value (5th-order) predictor-corrector, one force evaluation per step at the
//            predicted positions and velocities (Allen & Tildesley App. E; corrector c0 = 3/16 because
//            damping and friction make forces velocity-dependent). physics/polygon-dem.md §6.
//   verlet : velocity Verlet; velocity-dependent forces see the velocity v + dt·a_old.
// Coordinates a model prescribes (moving boundary layers) are overwritten every step through
// System::prescribe and never integrated.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/scene.hpp"
#include "core/state_archive.hpp"
#include "core/state_registry.hpp"

namespace frac::dynamics {

class System {
 public:
  virtual ~System() = default;
  // Accelerations at (t, q, v) into a (all of size n). Called once per step; must not allocate.
  virtual void accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) = 0;
  // The coordinates this system prescribes, and their values at time t (written into q, v, a at those
  // indices only). The default prescribes nothing.
  virtual std::span<const std::size_t> prescribed() const { return {}; }
  // The coordinates form this many equal blocks, one per component (the DEM: 3, x, y and φ of every
  // cell). The integrator's loops give each thread the same part of every block (for_coordinate_ranges,
  // core/parallel.hpp), the part of the cells the model's per-cell loops give it.
  virtual std::size_t coordinate_blocks() const { return 1; }
  virtual void prescribe(double /*t*/, std::span<double> /*q*/, std::span<double> /*v*/,
                         std::span<double> /*a*/) const {}

  // The evaluation as phases (core/phases) of a step that runs the integrator's phases and these on one team:
  // bind(t, q, v, a) before each run (outside the team), then the phases write a at (t, q, v). The default: one
  // serial phase that calls accelerations at the bound state. The phases call this object: take them once it is
  // in place.
  virtual void bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a);
  virtual Phases force_phases();
  // The team its evaluation runs on (core/phases: team_size); a step's team is the larger of it and the
  // integrator's (from kMinParallelCoordinates coordinates).
  virtual std::size_t team_size() const { return 1; }

 protected:
  double bound_t_ = 0;  // the bound state
  std::span<const double> bound_q_, bound_v_;
  std::span<double> bound_a_;
};

enum class IntegratorKind { gear5, verlet };

// How gear5's higher derivatives r3..r5 start (Verlet carries none: both mean the same to it).
//   zero  : r3 = r4 = r5 = 0, the usual start; limits gear5's global accuracy to O(dt²).
//   exact : d³q/dt³ .. d⁵q/dt⁵ at t0 from the equations of motion (taylor_derivatives below); gear5 is
//           then O(dt⁵) on a smooth problem (physics/polygon-dem.md §6).
enum class StartKind { zero, exact };
// "zero" or "exact"; UsageError naming `option` otherwise.
StartKind parse_start_kind(std::string_view name, std::string_view option);
std::string_view name(StartKind start);

// "gear5" or "verlet"; UsageError naming `option` otherwise.
IntegratorKind parse_integrator_kind(std::string_view name, std::string_view option);
std::string_view name(IntegratorKind kind);

// The most steps a run may need to reach stop.t_max: a step that needs more (1e-300 s) would never end.
inline constexpr double kMostSteps = 1e12;
// integrator.dt of a scene: 0 for "auto" (the model picks a stable step), else a positive step reaching `t_max`
// in at most kMostSteps steps; UsageError naming the key, the value and the count otherwise.
double read_time_step(Scene& scene, double t_max);

// The largest ω·dt for which the scheme stays stable on an undamped harmonic oscillator ẍ = −ω²x
// (measured by tests/unit/test_integrator.cpp). The time-step check divides it by ω_max.
double stability_limit(IntegratorKind kind);
// The largest γ·dt for which the scheme stays stable on a pure dashpot ẍ = −γẋ (gear5 0.163, Verlet 1,
// measured by tests/unit/test_integrator.cpp). Damping and friction add this second bound.
double damping_limit(IntegratorKind kind);

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Sets q(t0) = q0, v(t0) = v0 and evaluates the initial accelerations.
  // For gear5 the higher derivatives start at zero (the usual start; limits global accuracy to O(dt²));
  // Gear5::start_exact, or start() below with StartKind::exact, gives them exactly.
  virtual void start(System& system, double t0, double dt, std::span<const double> q0, std::span<const double> v0) = 0;
  // Advances by one step of dt: the phases of step_phases(system) on a team when worth it.
  void step(System& system);
  // One step as phases (core/phases): the integrator's (predict, the prescribed coordinates, correct, its clock)
  // around the system's force phases, then `after` (an engine's own: breaking). An engine that appends phases
  // runs the list itself, begin_step(system) before each run, on a team when team_for(system).
  virtual Phases step_phases(System& system, const Phases& after = {}) = 0;
  virtual void begin_step(System& system) = 0;
  std::size_t team_for(const System& system) const {
    return std::max(system.team_size(), frac::team_size(n_ > kMinParallelCoordinates));
  }
  // The phase list step() runs (its times: where a step's time goes).
  const Phases& step_list() const { return step_; }

  virtual IntegratorKind kind() const = 0;
  // Current state (after the last step): positions, velocities, accelerations.
  virtual std::span<const double> q() const = 0;
  virtual std::span<const double> v() const = 0;
  virtual std::span<const double> a() const = 0;
  // Mutable access, for a model that must change the state between steps (e.g. a kick).
  // For gear5, changing v resets nothing else: the next step's corrector takes it from there.
  virtual void set_velocity(std::size_t i, double value) = 0;
  double t() const { return t_; }
  double dt() const { return dt_; }
  std::size_t size() const { return n_; }
  long long steps() const { return steps_; }
  // Whether the last step left every integrated coordinate and velocity finite (checked in the step's last
  // pass over them, at no extra pass; prescribed coordinates follow the scene's motion).
  bool finite() const { return finite_; }
  // The state a continuation needs (core/state_registry), under "integrator/": time, step count, and the
  // per-cell fields positions q, velocities v, accelerations a and gear5's higher derivatives r1..r5, the system's
  // coordinate blocks a cell. Loading needs a started integrator of the same size.
  virtual void declare_state(StateRegistry& registry) = 0;
  void visit_state(StateArchive& archive);  // (its registry alone)

 protected:
  void declare_clock(StateRegistry& registry);
  std::size_t blocks_ = 1;  // the system's coordinate blocks: components a cell
  // The clock phase that ends a step: t += dt, one step more, finite from the threads' `bad` flags.
  Phase clock_phase(const TeamSlots<int>& bad);
  Phases step_;
  const System* step_system_ = nullptr;  // the system step_ was made for (none: made anew)
  bool finite_ = true;
  double t_ = 0, dt_ = 0;
  std::size_t n_ = 0;
  long long steps_ = 0;
};

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind);

// The derivatives d^k q/dt^k, k = 0..5, at t0 of the solution through q(t0) = q0, v(t0) = v0, from the
// equations of motion alone (what Gear5::start_exact needs). Method: the trajectory on [t0 − tau,
// t0 + tau] as a polynomial collocated at 10 Chebyshev points, found by Picard iteration: the
// accelerations a(t, q, v) at the points are fitted by a polynomial of degree 9, integrated twice from
// (q0, v0), and the points moved onto the result, until the points stop moving (to rounding). Then
// q'' = a(t0), and q''', q'''', q^(5) are the first three derivatives of the fitted a(t) at t0.
// Velocity- and time-dependent forces and prescribed coordinates enter as they do in a step.
// tau must resolve the fastest motion: at tau·ω_max = 0.1 a pass contracts the error by ~1e-2 and the
// polynomial is exact to ~1e-18 relative. RuntimeError if the iteration diverges or the highest terms
// of the polynomial show that it does not resolve the motion (tau too long).
struct TaylorStart {
  std::vector<std::vector<double>> derivs;  // derivs[k][i] = d^k q_i/dt^k at t0, k = 0..5
  int iterations = 0;                       // Picard passes
  int evaluations = 0;                      // calls of System::accelerations
  double residual = 0;                      // last change of the points, relative to their excursion
};
TaylorStart taylor_derivatives(System& system, double t0, std::span<const double> q0, std::span<const double> v0,
                               double tau);

// Starts `integrator` at t0 with step dt from (q0, v0): the usual start, or, for gear5 with
// start = exact, Gear5::start_exact from taylor_derivatives(system, t0, q0, v0, tau). Returns the
// force evaluations the exact start spent (0 for the usual start).
int start(Integrator& integrator, System& system, double t0, double dt, std::span<const double> q0,
          std::span<const double> v0, StartKind start, double tau);

// Gear's scheme, also usable directly (tests set exact initial derivatives).
// Gear's 5th-order loops on the coordinates [first, last) of the scaled derivatives r0 = q, r1 = dt·v, ...,
// r5 = dt^5/5!·q^(5) (Gear5's state, each a pointer to where coordinate 0 would sit, so that a part laid out
// apart is passed shifted): the predictor (Pascal's triangle; v = r1/dt), and the corrector from the
// accelerations a at the predicted state (returns 1 if a corrected q or v is not finite). Element by element:
// any split of [0, n) gives the same bits.
void gear5_predict(std::size_t first, std::size_t last, double* __restrict r0, double* __restrict r1,
                   double* __restrict r2, double* __restrict r3, double* __restrict r4, const double* __restrict r5,
                   double* __restrict v, double inv_dt);
int gear5_correct(std::size_t first, std::size_t last, double* __restrict r0, double* __restrict r1,
                  double* __restrict r2, double* __restrict r3, double* __restrict r4, double* __restrict r5,
                  double* __restrict v, const double* __restrict a, double half_dt2, double inv_dt);

class Gear5 final : public Integrator {
 public:
  void start(System& system, double t0, double dt, std::span<const double> q0, std::span<const double> v0) override;
  // Exact start for convergence tests: derivs[k][i] = d^k q_i/dt^k at t0, k = 0..5 (k = 2 is
  // recomputed from the system).
  void start_exact(System& system, double t0, double dt, const std::vector<std::vector<double>>& derivs);
  Phases step_phases(System& system, const Phases& after = {}) override;
  void begin_step(System& system) override;
  IntegratorKind kind() const override { return IntegratorKind::gear5; }
  std::span<const double> q() const override { return r_[0]; }
  std::span<const double> v() const override { return v_; }
  std::span<const double> a() const override { return a_; }
  void set_velocity(std::size_t i, double value) override;
  void declare_state(StateRegistry& registry) override;

 private:
  void apply_prescribed(const System& system, double t);
  TeamSlots<int> bad_;  // per thread: whether a corrected value it wrote is not finite
  // Scaled derivatives r_k = dt^k/k! · d^k q/dt^k: r_[0] = q in the system's layout, r_[1..5] (which only the
  // step's loops touch) in layout_, the threads' parts apart (core/parallel.hpp: PartLayout).
  std::vector<double> r_[6];
  std::vector<double> v_, a_;
  PartLayout layout_;
  double& r(int k, std::size_t i) { return r_[k][layout_.index(i)]; }
};

class VelocityVerlet final : public Integrator {
 public:
  void start(System& system, double t0, double dt, std::span<const double> q0, std::span<const double> v0) override;
  Phases step_phases(System& system, const Phases& after = {}) override;
  void begin_step(System& system) override;
  IntegratorKind kind() const override { return IntegratorKind::verlet; }
  std::span<const double> q() const override { return q_; }
  std::span<const double> v() const override { return v_; }
  std::span<const double> a() const override { return a_; }
  void set_velocity(std::size_t i, double value) override { v_[i] = value; }
  void declare_state(StateRegistry& registry) override;

 private:
  std::vector<double> q_, v_, a_, v_est_;
  TeamSlots<int> bad_;  // per thread: whether a value it wrote in the last kick is not finite
};

}  // namespace frac::dynamics
