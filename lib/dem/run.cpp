#include "dem/run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "dem/frames.hpp"

namespace frac::dem {
namespace {

// Names the step, the cell and the term of a non-finite value.
std::string blame_non_finite(const Model& model, const dynamics::Integrator& in, std::int64_t step) {
  const std::size_t n = model.bodies().n;
  const char* what[3] = {"x", "y", "angle"};
  std::ostringstream msg;
  msg << "non-finite value at step " << step << " (t = " << in.t() << " s)";
  if (!model.non_finite_term().empty()) {
    const std::size_t k = model.non_finite_index();
    msg << ": the " << model.non_finite_term() << " force on cell " << k % n << " (" << what[k / n] << ")";
  } else {
    const auto q = in.q();
    const auto v = in.v();
    for (std::size_t k = 0; k < q.size(); ++k)
      if (!std::isfinite(q[k]) || !std::isfinite(v[k])) {
        msg << ": the state of cell " << k % n << " (" << what[k / n] << ") in the integrator";
        break;
      }
  }
  msg << "; the time step may be too large for this scene";
  return msg.str();
}

bool is_paper_law(const std::string& name) {
  for (const ContactLawRow& row : contact_law_table())
    if (row.name == name) return true;
  return false;
}

}  // namespace

DemRun::DemRun(Model& model, dynamics::Integrator& integrator, const mesh::CellMesh& mesh, const DemScene& scene,
               const LoadingSetup& setup, std::vector<double> q0, std::vector<double> v0, double dt, double start_tau)
    : model_(model),
      integrator_(integrator),
      mesh_(mesh),
      scene_(scene),
      setup_(setup),
      q0_(std::move(q0)),
      v0_(std::move(v0)),
      dt_(dt),
      start_tau_(start_tau),
      state_(model.bodies().n) {
  ledger_.law_work.assign(model_.contact_laws().size(), 0.0);
  previous_power_.assign(model_.contact_laws().size(), 0.0);
  next_frame_ = scene_.output.frame_interval;
  make_observables();
  make_frames();
}

void DemRun::start() {
  runaway_.emplace(q0_, model_.bodies().n, "cell");
  start_evaluations_ = dynamics::start(integrator_, model_, 0.0, dt_, q0_, v0_, scene_.integrator.start, start_tau_);
  std::vector<double>().swap(q0_);  // (the integrator's state from here on)
  std::vector<double>().swap(v0_);
  for (std::size_t l = 0; l < previous_power_.size(); ++l) previous_power_[l] = model_.law_power(l);
  previous_boundary_power_ = model_.boundary_power();
  declare_state();  // (the integrator's fields are the size the start gave them)
}

// Everything the run carries from step to step: what a checkpoint saves and a continuation loads.
void DemRun::declare_state() {
  integrator_.declare_state(state_);
  model_.declare_state(state_);
  state_.other([this](StateArchive& a) {
    const std::size_t laws = model_.contact_laws().size(), nb = model_.beams().size();
    StateArchive::Scope scope(a, "run");
    a.value("next_frame", next_frame_);
    a.value("last_break_step", last_break_step_);
    a.array("law_work", ledger_.law_work, laws);
    a.value("boundary_work", ledger_.boundary);
    a.value("broken_energy", ledger_.broken_energy);
    a.array("previous_law_power", previous_power_, laws);
    a.value("previous_boundary_power", previous_boundary_power_);
    a.value("initial_balance", e0_);
    a.value("energy_error", energy_error_);
    a.value("energy_scale", energy_scale_);
    a.value("start_evaluations", start_evaluations_);
    std::size_t broken_count = broken_.size();
    a.value("broken", broken_count);
    if (a.loading()) {
      if (broken_count > nb) a.refuse("broken", "more broken beams than the mesh has");
      broken_.assign(broken_count, BeamBreak{});
    }
    a.field("broken_beam", broken_, &BeamBreak::beam);
    a.field("broken_mode", broken_, &BeamBreak::mode);
    a.field("broken_energy_each", broken_, &BeamBreak::energy);
  });
}

Phases DemRun::step_phases() {
  // The integrator's phases around the model's, then the breaking pass (on the state the step ends in).
  return integrator_.step_phases(model_, model_.physics().breaking ? model_.beams().breaking_phases() : Phases{});
}

void DemRun::bind_step() {
  broken_before_ = broken_.size();
  if (model_.physics().breaking)
    model_.beams().bind_breaking(integrator_.q(), model_.material().t_eps, model_.material().t_theta, broken_);
  integrator_.begin_step(model_);
}

void DemRun::after_step(std::int64_t step, std::vector<run::Event>& events) {
  // Ledger: the power of each term integrated by the trapezoidal rule between force evaluations.
  for (std::size_t l = 0; l < previous_power_.size(); ++l) {
    ledger_.law_work[l] += 0.5 * (previous_power_[l] + model_.law_power(l)) * dt_;
    previous_power_[l] = model_.law_power(l);
  }
  ledger_.boundary += 0.5 * (previous_boundary_power_ + model_.boundary_power()) * dt_;
  previous_boundary_power_ = model_.boundary_power();
  if (!model_.non_finite_term().empty() || !integrator_.finite())
    throw RuntimeError(blame_non_finite(model_, integrator_, step));
  for (std::size_t k = broken_before_; k < broken_.size(); ++k) {
    ledger_.broken_energy += broken_[k].energy;
    events.push_back({broken_[k].beam, static_cast<std::uint8_t>(broken_[k].mode)});
  }
  if (broken_.size() > broken_before_) last_break_step_ = step;
}

std::string DemRun::stop_reason(std::int64_t step) const {
  const StopRule& stop = scene_.stop;
  if (integrator_.t() >= stop.t_max * (1 - 1e-12)) return "t_max";
  if (step >= stop.max_steps) return "max_steps";
  if (model_.physics().breaking && stop.steps_without_breaking > 0 && last_break_step_ >= 0 &&
      step - last_break_step_ >= stop.steps_without_breaking)
    return "no beam broke for " + std::to_string(stop.steps_without_breaking) + " steps";
  return "";
}

bool DemRun::frame_due() const { return integrator_.t() >= next_frame_ * (1 - 1e-12); }

void DemRun::frame_written() {
  // An interval shorter than a step: one frame a step, the frames passed over skipped at once (not one by one:
  // 1e-300 s would loop for ever).
  const double t = integrator_.t(), fi = scene_.output.frame_interval, now = t * (1 + 1e-12);
  next_frame_ += std::max(0.0, std::floor((now - next_frame_) / fi)) * fi;  // (0 for an interval of a step or more)
  while (next_frame_ <= now) {
    const double after = next_frame_ + fi;
    next_frame_ = after > next_frame_ ? after : t * (1 + 2e-12);
  }
}

void DemRun::measure(std::int64_t step) {
  const auto q = integrator_.q();
  runaway_->check(q, step, integrator_.t());
  measured_.kinetic = model_.kinetic_energy(integrator_.v());
  measured_.beam_energy = model_.physics().beams ? model_.beams().energy(q) : 0.0;
  // The work done against each law (the energy it stored or dissipated), in the laws' order.
  double against_laws = 0;
  for (const double w : ledger_.law_work) against_laws -= w;
  measured_.balance = measured_.kinetic[0] + measured_.kinetic[1] + measured_.beam_energy + against_laws +
                      ledger_.broken_energy - ledger_.boundary;
  if (step == 0) e0_ = measured_.balance;
  energy_error_ = std::max(energy_error_, std::abs(measured_.balance - e0_));
  energy_scale_ = std::max({energy_scale_, std::abs(e0_), std::abs(ledger_.boundary)});
}

double DemRun::law_work(const std::string& name) const {
  const ContactLaws& laws = model_.contact_laws();
  for (std::size_t l = 0; l < laws.size(); ++l)
    if (laws.names[l] == name) return ledger_.law_work[l];
  return 0.0;
}

void DemRun::make_observables() {
  auto add = [&](std::string name, std::string unit, std::function<double()> value) {
    observables_.push_back({std::move(name), std::move(unit), std::move(value)});
  };
  add("kinetic_energy_translational", "J", [this] { return measured_.kinetic[0]; });
  add("kinetic_energy_rotational", "J", [this] { return measured_.kinetic[1]; });
  add("beam_energy", "J", [this] { return measured_.beam_energy; });
  // The paper's laws' work always (zero when off), then any other law's.
  for (const ContactLawRow& row : contact_law_table())
    add(row.name + "_work", "J", [this, name = row.name] { return -law_work(name); });
  const ContactLaws& laws = model_.contact_laws();
  for (std::size_t l = 0; l < laws.size(); ++l)
    if (!is_paper_law(laws.names[l])) add(laws.names[l] + "_work", "J", [this, l] { return -ledger_.law_work[l]; });
  add("broken_beam_energy", "J", [this] { return ledger_.broken_energy; });
  add("boundary_work", "J", [this] { return ledger_.boundary; });
  add("energy_balance", "J", [this] { return measured_.balance; });
  add("intact_beams", "1", [this] { return static_cast<double>(model_.beams().intact_count()); });
  add("contacts", "1", [this] { return static_cast<double>(model_.contacts().size()); });
  if (!setup_.probe.active) return;
  const std::size_t n = model_.bodies().n;
  add("stress", "Pa", [this, n] { return setup_.probe.stress(model_.forces(), n); });
  add("axial_strain", "1", [this, n] { return setup_.probe.axial_strain(integrator_.q(), n); });
  add("lateral_strain", "1", [this, n] { return setup_.probe.lateral_strain(integrator_.q(), n); });
}

void DemRun::make_frames() {
  frames_ = run::frame_datasets(frame_table(), scene_.output.frames, model_, integrator_, model_.bodies().n,
                                model_.beams().size());
}

run::RunBodies DemRun::bodies() const { return {&mesh_, nullptr, model_.bodies().mass, model_.bodies().inertia}; }

std::string DemRun::progress_line(std::int64_t step, std::int64_t first_step, double first_t, double elapsed) const {
  std::ostringstream s;
  s.precision(3);
  const double t = integrator_.t();
  s << "t = " << t << " s, step " << step << ", " << static_cast<double>(step - first_step) / std::max(elapsed, 1e-9)
    << " steps/s, " << broken_.size() << " beams broken, ETA "
    << (scene_.stop.t_max - t) / std::max(t - first_t, 1e-30) * elapsed << " s (at most)";
  return s.str();
}

RunSummary DemRun::summary(const run::Outcome& outcome) const {
  RunSummary s;
  s.steps = outcome.steps;
  s.time = outcome.time;
  s.dt = dt_;
  s.broken = static_cast<std::int64_t>(broken_.size());
  s.stop_reason = outcome.stop_reason;
  s.energy_error = energy_error_;
  s.energy_scale = energy_scale_;
  s.wall_seconds = outcome.wall_seconds;
  s.start_evaluations = start_evaluations_;
  s.phases = outcome.phases;
  return s;
}

}  // namespace frac::dem
