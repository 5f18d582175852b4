#include "rubber/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <new>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/rng.hpp"
#include "core/signals.hpp"
#include "dynamics/runaway.hpp"
#include "rubber/frames.hpp"
#include "rubber/lattice.hpp"
#include "rubber/three_body_residual.hpp"

namespace frac::rubber {

ModelOptions model_options(const RubberSetup& su, int threads) {
  const RubberScene& sc = su.scene;
  ModelOptions mo;
  mo.law = su.law;
  mo.node_mass = su.node_mass;
  mo.damping = sc.damping ? sc.damping_kind : DampingKind::none;
  mo.beta = sc.beta;
  mo.damping_onset = sc.damping_onset;
  mo.failure = sc.failure == "freeze" ? Failure::freeze : Failure::paper;
  mo.break_extra = sc.irreversible ? sc.break_widths * sc.cutoff_width : std::numeric_limits<double>::infinity();
  mo.threads = threads;
  return mo;
}

// Homogeneous pre-stretch about the origin of the mesh: the sheet starts in equilibrium. With
// loading.ramp_time, it starts at λy = loading.ramp_from_y instead, moving at the homogeneous stretch rate
// (v_y = λ̇y r_y, so no wave starts from the grips), which the clamped rows keep until ramp_time. Returns λ̇y.
double pre_stretch(RubberSystem& sys, const RubberSetup& su) {
  const RubberScene& sc = su.scene;
  const Lattice& L = sys.model->lattice();
  const std::size_t n = L.n;
  Eigen::Matrix2d F0 = su.F;
  const double rate_y = sc.ramp_time > 0 ? (sc.stretch_y - sc.ramp_from_y) / sc.ramp_time : 0.0;
  if (sc.ramp_time > 0) F0(1, 1) = sc.ramp_from_y;
  sys.q0.resize(2 * n);
  sys.v0.assign(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    sys.q0[i] = F0(0, 0) * L.rx[i] + F0(0, 1) * L.ry[i];
    sys.q0[n + i] = F0(1, 0) * L.rx[i] + F0(1, 1) * L.ry[i];
    sys.v0[n + i] = rate_y * L.ry[i];
  }
  return rate_y;
}

// The seed crack, along the mesh's crack line from the left edge; the bulk off the line tougher; the drive.
void seed_crack(RubberSystem& sys, const RubberSetup& su) {
  const RubberScene& sc = su.scene;
  Model& model = *sys.model;
  const double path_length = sys.path->x_max() - sys.path->x_min();
  if (sc.seed_length >= path_length && sc.seed_length > 0) {
    std::ostringstream msg;
    msg << "crack.seed_length = " << sc.seed_length << " m: not shorter than the crack line across the sheet ("
        << path_length << " m)";
    throw UsageError(msg.str());
  }
  if (sc.seed_length > 0) sys.seeded = sys.path->seed(model, sc.seed_length);
  if (sc.path_cutoff_ratio != 1) sys.path->set_bulk_cutoff(model, sc.path_cutoff_ratio * sc.cutoff_length);
  if (sc.drive_speed > 0)
    sys.drive = std::make_unique<CrackDrive>(*sys.path, sc.seed_length, sc.drive_speed, sc.drive_length, su.F(0, 0));
}

// A localized pulse: Gaussian displacement (standard deviation pulse.width) of the lines across the
// direction of propagation, along it (longitudinal) or across it (shear).
void add_pulse(std::vector<double>& q0, const Lattice& L, const RubberScene& sc) {
  const std::size_t n = L.n;
  const bool along_x = sc.pulse_direction == "x";
  const auto& s = along_x ? L.rx : L.ry;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  const double s0 = *lo + sc.pulse_position * (*hi - *lo);
  const bool disp_x = along_x == (sc.pulse_kind == "longitudinal");
  for (std::size_t i = 0; i < n; ++i) {
    const double z = (s[i] - s0) / sc.pulse_width;
    const double u = sc.pulse_amplitude * std::exp(-0.5 * z * z);
    q0[disp_x ? i : n + i] += u;
  }
}

// Clamps: rows j < k and j >= ny - k (top and bottom), columns likewise (index = j nx + i).
std::vector<std::size_t> clamped_nodes(const mesh::NodeMesh& mesh, const RubberScene& sc, std::size_t n) {
  std::vector<std::size_t> clamped;
  const auto nx = static_cast<std::size_t>(mesh.nx), ny = static_cast<std::size_t>(mesh.ny);
  const auto kr = static_cast<std::size_t>(sc.clamp_rows), kc = static_cast<std::size_t>(sc.clamp_columns);
  if ((kr > 0 || kc > 0) && nx * ny != n) throw InputError("clamps need an nx x ny mesh");
  for (std::size_t j = 0; j < ny && (kr > 0 || kc > 0); ++j)
    for (std::size_t i = 0; i < nx; ++i)
      if (j < kr || j + kr >= ny || i < kc || i + kc >= nx) clamped.push_back(j * nx + i);
  return clamped;
}

// Thermal noise: uniform velocities in [−noise, noise] with zero mean over the free nodes.
void add_thermal_noise(std::vector<double>& v0, std::span<const std::size_t> clamped, std::size_t n, std::uint64_t seed,
                       double noise) {
  Rng rng(seed);
  std::vector<std::uint8_t> fixed(n, 0);
  for (std::size_t i : clamped) fixed[i] = 1;
  std::size_t free = 0;
  double mean[2] = {0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 2; ++c) {
      const double v = rng.uniform(-noise, noise);
      if (fixed[i]) continue;
      v0[static_cast<std::size_t>(c) * n + i] += v;
      mean[c] += v;
    }
  for (std::size_t i = 0; i < n; ++i) free += fixed[i] ? 0 : 1;
  for (std::size_t i = 0; i < n && free > 0; ++i)
    if (!fixed[i])
      for (int c = 0; c < 2; ++c) v0[static_cast<std::size_t>(c) * n + i] -= mean[c] / static_cast<double>(free);
}

// Tip kick: the two nodes of the first intact bond ahead of the tip move apart in y.
void kick_tip(RubberSystem& sys, double tip_kick) {
  const Lattice& L = sys.model->lattice();
  const std::size_t n = L.n;
  const std::size_t k = sys.path->next_intact(*sys.model, sys.q0);
  if (k < sys.path->size()) {
    const std::size_t b = sys.path->bond(k), i = b / 3, j = L.bond_other(b);
    const double yi = L.ry[i] > sys.path->line_y() ? 1.0 : -1.0;
    sys.v0[n + i] += yi * tip_kick;
    sys.v0[n + j] -= yi * tip_kick;
  }
}

RubberSystem build_rubber(const mesh::NodeMesh& mesh, const RubberSetup& su, std::uint64_t seed, int threads) try {
  const RubberScene& sc = su.scene;
  RubberSystem sys;
  ModelOptions mo = model_options(su, threads);
  Lattice lattice = build_lattice(mesh, sc.periodic_x, sc.periodic_y);
  if (sc.three_body_residual > 0) mo.residual = three_body_residual(su.law, lattice, su.F, sc.three_body_residual);
  sys.model = std::make_unique<Model>(std::move(lattice), mo);
  Model& model = *sys.model;
  const Lattice& L = model.lattice();
  const std::size_t n = L.n;
  model.set_box(su.F);
  sys.path = std::make_unique<CrackPath>(mesh, L);
  const double rate_y = pre_stretch(sys, su);
  seed_crack(sys, su);
  if (sc.pulse_amplitude > 0) add_pulse(sys.q0, L, sc);
  const std::vector<std::size_t> clamped = clamped_nodes(mesh, sc, n);
  if (!clamped.empty()) {
    if (sc.ramp_time > 0)
      model.clamp(clamped, sys.q0, sys.v0, sc.ramp_time);
    else
      model.clamp(clamped, sys.q0);
  }
  if (sc.noise > 0) add_thermal_noise(sys.v0, clamped, n, seed, sc.noise);
  if (sc.tip_kick > 0) kick_tip(sys, sc.tip_kick);
  for (std::size_t i : clamped) {
    sys.v0[i] = 0;
    sys.v0[n + i] = rate_y * L.ry[i];
  }
  return sys;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the rubber lattice of " + std::to_string(mesh.nodes()) + " nodes");
}

void SpeedFit::add(double tt, double xx) {
  t[head] = tt;
  x[head] = xx;
  head = (head + 1) % t.size();
  count = std::min(count + 1, t.size());
}

double SpeedFit::slope() const {
  if (count < 2) return 0;
  const std::size_t start = (head + t.size() - count) % t.size();
  double mt = 0, mx = 0;
  for (std::size_t k = 0; k < count; ++k) {
    mt += t[(start + k) % t.size()];
    mx += x[(start + k) % t.size()];
  }
  mt /= static_cast<double>(count);
  mx /= static_cast<double>(count);
  double stt = 0, stx = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double dt = t[(start + k) % t.size()] - mt;
    stt += dt * dt;
    stx += dt * (x[(start + k) % t.size()] - mx);
  }
  return stt > 0 ? stx / stt : 0;
}

namespace {
// The speed window in observations.
std::size_t speed_window(const RubberScene& sc, double dt) {
  return static_cast<std::size_t>(
      std::min(1e6, std::ceil(sc.speed_window / (static_cast<double>(sc.observe_every) * dt)) + 1));
}
}  // namespace

RubberRun::RubberRun(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh)
    : sys_(system),
      setup_(setup),
      mesh_(mesh),
      model_(*system.model),
      integ_(dynamics::make_integrator(setup.scene.integrator)),
      fit_(speed_window(setup.scene, setup.dt)),
      next_frame_(setup.scene.frame_interval > 0 ? setup.scene.frame_interval : 1e300),
      state_(model_.lattice().n) {
  sum_.dt = setup.dt;
  events_.reserve(model_.lattice().bonds());
  make_observables();
  make_frames();
}

void RubberRun::start() {
  integ_->start(model_, 0.0, setup_.dt, sys_.q0, sys_.v0);
  tip_ = sys_.path->tip(model_, integ_->q());
  sum_.tip_start = tip_;
  runaway_.emplace(integ_->q(), model_.lattice().n, "node");
  declare_state();  // (the integrator's fields are the size the start gave them)
}

// Everything the run carries from step to step: what a checkpoint saves and a continuation loads.
void RubberRun::declare_state() {
  integ_->declare_state(state_);
  state_.other([this](StateArchive& a) { model_.visit_state(a); });
  if (sys_.drive) state_.other([this](StateArchive& a) { sys_.drive->visit_state(a); });
  state_.other([this](StateArchive& a) {
    StateArchive::Scope scope(a, "run");
    a.value("next_frame", next_frame_);
    a.value("events", sum_.events);
    a.value("irreversible", sum_.irreversible);
    a.value("toughened", sum_.toughened);
    a.value("driven", sum_.driven);
    a.value("drive_energy", sum_.drive_energy);
    a.value("energy_start", sum_.energy_start);
    a.value("energy_end", sum_.energy_end);
    a.value("energy_conserved_set", sum_.energy_conserved_set);
    a.value("energy_conserved", sum_.energy_conserved);
    a.value("energy_conserved_time", sum_.energy_conserved_time);
    a.value("drive_energy_conserved", sum_.drive_energy_conserved);
    a.value("tip_speed", sum_.tip_speed);
    for (auto [name, t] : {std::pair{"tip", &tip_}, std::pair{"tip_start", &sum_.tip_start}}) {
      StateArchive::Scope tip_scope(a, name);
      a.value("found", t->found);
      a.value("bond", t->bond);
      a.value("reference_x", t->reference_x);
      a.value("lab_x", t->lab_x);
      a.value("broken", t->broken);
    }
    StateArchive::Scope fit_scope(a, "speed_fit");
    a.array("t", fit_.t, fit_.t.size());
    a.array("x", fit_.x, fit_.x.size());
    a.value("head", fit_.head);
    a.value("count", fit_.count);
    if (a.loading() && (fit_.head >= fit_.t.size() || fit_.count > fit_.t.size()))
      a.refuse("head", "outside the speed window");
  });
}

void RubberRun::after_step(std::int64_t step, std::vector<run::Event>& events) {
  const RubberScene& sc = setup_.scene;
  if (model_.nonfinite() > 0) [[unlikely]] {
    std::ostringstream msg;
    msg.precision(6);
    msg << "non-finite force at step " << step << " (t = " << integ_->t()
        << " s): " << model_.diagnose_nonfinite(integ_->q(), integ_->a())
        << "; the time step may be too large for this scene";
    throw RuntimeError(msg.str());
  }
  if (sys_.drive && !sys_.drive->finished()) {
    double change = 0;
    sum_.driven += sys_.drive->cut(model_, integ_->t(), integ_->q(), change);
    sum_.drive_energy += change;
  }
  if (model_.pending_events() > 0 || model_.pending_breaks() > 0) {
    events_.clear();
    model_.take_events(events_);
    sum_.events += events_.size();
    sum_.irreversible += static_cast<std::size_t>(model_.pending_breaks());
    model_.clear_breaks();
    for (std::size_t b : events_) {
      const std::int64_t k = model_.lattice().mesh_bond[b];
      if (k >= 0) events.push_back({k, 1});
    }
  }
  if (sc.toughening && step % sc.toughening_every == 0)
    sum_.toughened += model_.toughen(integ_->q(), sc.toughening_trigger, sc.toughening_cutoff);
}

std::string RubberRun::stop_reason(std::int64_t step) const {
  if (tip_stop_) return "the crack tip reached stop.tip_margin from the far edge";
  if (integ_->t() >= setup_.scene.t_max - 0.5 * setup_.dt) return "stop.t_max reached";
  if (step >= setup_.scene.max_steps) return "stop.max_steps reached";
  return "";
}

void RubberRun::measure(std::int64_t step) {
  const RubberScene& sc = setup_.scene;
  const auto q = integ_->q();
  runaway_->check(q, step, integ_->t());
  kinetic_ = model_.kinetic_energy(integ_->v());
  energy_ = model_.potential_energy(q);
  const double e = kinetic_ + energy_.total();
  tip_ = sys_.path->tip(model_, q);
  // The speed is fitted to λx × reference x of the tip: the lab position of the crack in the far field (the
  // tip's own nodes may fly off as debris).
  if (tip_.found) fit_.add(integ_->t(), setup_.F(0, 0) * tip_.reference_x);
  sum_.tip_speed = fit_.slope();
  sum_.energy_end = e;
  if (step == 0) sum_.energy_start = e;
  // The clamped rows move (and work on the sheet) until loading.ramp_time.
  if (!sum_.energy_conserved_set && integ_->t() >= (sc.ramp_time > 0 ? sc.ramp_time : 0.0)) {
    sum_.energy_conserved_set = true;
    sum_.energy_conserved = e;
    sum_.energy_conserved_time = integ_->t();
    sum_.drive_energy_conserved = sum_.drive_energy;
  }
  // (The time loop's observations only: not the first state's.)
  tip_stop_ = step > 0 && sc.tip_margin > 0 && tip_.found && tip_.reference_x > sys_.path->x_max() - sc.tip_margin;
}

void RubberRun::make_observables() {
  const RubberScene& sc = setup_.scene;
  auto add = [&](std::string name, std::string unit, std::function<double()> value) {
    observables_.push_back({std::move(name), std::move(unit), std::move(value)});
  };
  add("kinetic_energy", "J", [this] { return kinetic_; });
  add("potential_energy", "J", [this] { return energy_.total(); });
  add("total_energy", "J", [this] { return kinetic_ + energy_.total(); });
  add("bonds_past_cutoff", "1", [this] { return static_cast<double>(sum_.events); });
  add("crack_tip_x", "m", [this] { return tip_.found ? tip_.lab_x : std::nan(""); });
  add("crack_tip_reference_x", "m", [this] { return tip_.found ? tip_.reference_x : std::nan(""); });
  add("crack_tip_speed", "m s-1", [this] { return sum_.tip_speed; });
  if (sc.toughening) add("toughened_bonds", "1", [this] { return static_cast<double>(sum_.toughened); });
  if (sys_.drive) add("drive_energy", "J", [this] { return sum_.drive_energy; });
  if (model_.options().failure == Failure::freeze) add("frozen_energy", "J", [this] { return energy_.frozen; });
}

void RubberRun::make_frames() {
  frames_ = run::frame_datasets(frame_table(), setup_.scene.frames, model_, *integ_, model_.lattice().n,
                                model_.lattice().bond_id.size());
}

run::RunBodies RubberRun::bodies() const {
  return {nullptr, &mesh_, std::vector<double>(mesh_.nodes(), setup_.node_mass), {}};
}

std::string RubberRun::progress_line(std::int64_t step, std::int64_t, double, double) const {
  std::ostringstream s;
  s.precision(4);
  s << "t = " << integ_->t() << " s (" << std::lround(100 * integ_->t() / setup_.scene.t_max) << "%), step " << step;
  if (tip_.found)
    s << ", tip at x = " << tip_.lab_x << " m ("
      << (tip_.reference_x - sum_.tip_start.reference_x) / model_.lattice().spacing
      << " spacings), v = " << sum_.tip_speed << " m/s";
  s << ", " << sum_.events << " bonds past u_c";
  return s.str();
}

RubberSummary RubberRun::summary(const run::Outcome& outcome) const {
  RubberSummary s = sum_;
  s.loop_seconds = outcome.loop_seconds;
  s.nodes = model_.lattice().n;
  s.loop_steps = outcome.loop_steps;
  s.steps = outcome.steps;
  s.time = outcome.time;
  s.stop_reason = outcome.stop_reason;
  s.tip = tip_;
  s.wall_seconds = outcome.wall_seconds;
  s.phases = outcome.phases;
  return s;
}

RubberSummary run_rubber(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh,
                         Progress& progress) {
  RubberRun engine(system, setup, mesh);
  return engine.summary(run::drive(engine, progress));
}

}  // namespace frac::rubber
