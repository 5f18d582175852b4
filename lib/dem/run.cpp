#include "dem/run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "core/signals.hpp"
#include "dynamics/runaway.hpp"

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
    msg << ": the " << model.non_finite_term() << " force on cell " << k % n << " (" << what[k / n]
        << ")";
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

}  // namespace

RunSummary run_dem(Model& model, dynamics::Integrator& integrator, const DemScene& scene, const LoadingSetup& setup,
                   std::vector<double> q0, std::vector<double> v0, double dt, io::RunWriter* writer,
                   Progress& progress, double start_tau, const io::Continuation& continuation) {
  RunSummary summary;
  summary.dt = dt;
  const std::size_t n = model.bodies().n;
  const std::size_t nb = model.beams().size();
  Ledger ledger;
  std::vector<BeamBreak> broken;

  const dynamics::RunawayGuard runaway(q0, n, "cell");
  summary.start_evaluations =
      dynamics::start(integrator, model, 0.0, dt, q0, v0, scene.integrator.start, start_tau);
  std::vector<double>().swap(q0);  // (the integrator's state from here on)
  std::vector<double>().swap(v0);
  const ContactLaws& laws = model.contact_laws();
  ledger.law_work.assign(laws.size(), 0.0);
  std::vector<double> previous_power(laws.size());
  for (std::size_t l = 0; l < laws.size(); ++l) previous_power[l] = model.law_power(l);
  double previous_boundary_power = model.boundary_power();
  auto write_frame = [&](std::int64_t step) {
    if (!writer) return;
    // (Its buffers only while it is written: memory between frames, when the neighbour list is rebuilt.)
    io::BodyFrame frame;
    frame.position.resize(2 * n);
    frame.velocity.resize(2 * n);
    frame.angle.resize(n);
    frame.angular_velocity.resize(n);
    frame.intact.resize(nb);
    frame.strain.resize(nb);
    const auto q = integrator.q();
    const auto v = integrator.v();
    for (std::size_t k = 0; k < n; ++k) {
      frame.position[2 * k] = q[k];
      frame.position[2 * k + 1] = q[n + k];
      frame.velocity[2 * k] = v[k];
      frame.velocity[2 * k + 1] = v[n + k];
      frame.angle[k] = q[2 * n + k];
      frame.angular_velocity[k] = v[2 * n + k];
    }
    const auto intact = model.beams().intact();
    std::copy(intact.begin(), intact.end(), frame.intact.begin());
    model.beams().strains(q, frame.strain);
    frame.step = step;
    frame.time = integrator.t();
    writer->write_frame(frame);
  };
  // The work done by the law named `name` (0 when it is off).
  auto law_work = [&](const std::string& name) {
    for (std::size_t l = 0; l < laws.size(); ++l)
      if (laws.names[l] == name) return ledger.law_work[l];
    return 0.0;
  };
  auto is_paper_law = [](const std::string& name) {
    for (const ContactLawRow& row : contact_law_table())
      if (row.name == name) return true;
    return false;
  };
  double e0 = 0;
  auto observe = [&](std::int64_t step) {
    const auto q = integrator.q();
    runaway.check(q, step, integrator.t());
    const auto v = integrator.v();
    const auto ke = model.kinetic_energy(v);
    const double ub = model.physics().beams ? model.beams().energy(q) : 0.0;
    // The work done against each law (the energy it stored or dissipated), in the laws' order.
    double against_laws = 0;
    for (const double w : ledger.law_work) against_laws -= w;
    const double balance = ke[0] + ke[1] + ub + against_laws + ledger.broken_energy - ledger.boundary;
    if (step == 0) e0 = balance;
    summary.energy_error = std::max(summary.energy_error, std::abs(balance - e0));
    summary.energy_scale = std::max({summary.energy_scale, std::abs(e0), std::abs(ledger.boundary)});
    if (!writer) return;
    const double t = integrator.t();
    writer->observe("kinetic_energy_translational", step, t, ke[0], "J");
    writer->observe("kinetic_energy_rotational", step, t, ke[1], "J");
    writer->observe("beam_energy", step, t, ub, "J");
    // The paper's laws' work always (zero when off), then any other law's.
    for (const ContactLawRow& row : contact_law_table())
      writer->observe(row.name + "_work", step, t, -law_work(row.name), "J");
    for (std::size_t l = 0; l < laws.size(); ++l)
      if (!is_paper_law(laws.names[l])) writer->observe(laws.names[l] + "_work", step, t, -ledger.law_work[l], "J");
    writer->observe("broken_beam_energy", step, t, ledger.broken_energy, "J");
    writer->observe("boundary_work", step, t, ledger.boundary, "J");
    writer->observe("energy_balance", step, t, balance, "J");
    writer->observe("intact_beams", step, t, static_cast<double>(model.beams().intact_count()), "1");
    writer->observe("contacts", step, t, static_cast<double>(model.contacts().size()), "1");
    if (setup.probe.active) {
      writer->observe("stress", step, t, setup.probe.stress(model.forces(), n), "Pa");
      writer->observe("axial_strain", step, t, setup.probe.axial_strain(q, n), "1");
      writer->observe("lateral_strain", step, t, setup.probe.lateral_strain(q, n), "1");
    }
  };

  double next_frame = scene.output.frame_interval;
  std::int64_t last_break_step = -1;
  const StopRule& stop = scene.stop;
  const bool breaking = model.physics().breaking;
  std::int64_t step = 0;
  // Everything the loop carries from step to step: what a checkpoint saves and a continuation loads.
  const auto visit_state = [&](StateArchive& a) {
    integrator.visit_state(a);
    model.visit_state(a);
    StateArchive::Scope scope(a, "run");
    a.value("step", step);
    a.value("next_frame", next_frame);
    a.value("last_break_step", last_break_step);
    a.array("law_work", ledger.law_work, laws.size());
    a.value("boundary_work", ledger.boundary);
    a.value("broken_energy", ledger.broken_energy);
    a.array("previous_law_power", previous_power, laws.size());
    a.value("previous_boundary_power", previous_boundary_power);
    a.value("initial_balance", e0);
    a.value("energy_error", summary.energy_error);
    a.value("energy_scale", summary.energy_scale);
    a.value("start_evaluations", summary.start_evaluations);
    std::size_t broken_count = broken.size();
    a.value("broken", broken_count);
    if (a.loading()) {
      if (broken_count > nb) a.refuse("broken", "more broken beams than the mesh has");
      broken.assign(broken_count, BeamBreak{});
    }
    a.field("broken_beam", broken, &BeamBreak::beam);
    a.field("broken_mode", broken, &BeamBreak::mode);
    a.field("broken_energy_each", broken, &BeamBreak::energy);
  };
  if (continuation.resume) {
    visit_state(*continuation.resume);
  } else {
    observe(0);
    write_frame(0);
  }
  const std::int64_t first_step = step;  // (of this process: the rate and the ETA count from here)
  const double first_t = integrator.t();
  std::optional<DeferSignals> defer;
  if (continuation.checkpoints) defer.emplace();
  // A step: the integrator's phases around the model's, then the breaking pass (on the state the step ends in).
  Beams& beams = model.beams();
  Phases step_phases = integrator.step_phases(model, breaking ? beams.breaking_phases() : Phases{});
  const std::size_t team = integrator.team_for(model);
  for (;;) {
    const std::size_t before = broken.size();
    if (breaking) beams.bind_breaking(integrator.q(), model.material().t_eps, model.material().t_theta, broken);
    integrator.begin_step(model);
    step_phases.run(team);
    ++step;
    // Ledger: the power of each term integrated by the trapezoidal rule between force evaluations.
    for (std::size_t l = 0; l < laws.size(); ++l) {
      ledger.law_work[l] += 0.5 * (previous_power[l] + model.law_power(l)) * dt;
      previous_power[l] = model.law_power(l);
    }
    ledger.boundary += 0.5 * (previous_boundary_power + model.boundary_power()) * dt;
    previous_boundary_power = model.boundary_power();
    if (!model.non_finite_term().empty() || !integrator.finite())
      throw RuntimeError(blame_non_finite(model, integrator, step));
    if (breaking) {
      for (std::size_t k = before; k < broken.size(); ++k) {
        ledger.broken_energy += broken[k].energy;
        if (writer)
          writer->record_break({step, integrator.t(), broken[k].beam, static_cast<std::uint8_t>(broken[k].mode)});
      }
      if (broken.size() > before) last_break_step = step;
    }
    const double t = integrator.t();
    std::string reason;
    if (t >= stop.t_max * (1 - 1e-12)) reason = "t_max";
    else if (step >= stop.max_steps) reason = "max_steps";
    else if (breaking && stop.steps_without_breaking > 0 && last_break_step >= 0 &&
             step - last_break_step >= stop.steps_without_breaking)
      reason = "no beam broke for " + std::to_string(stop.steps_without_breaking) + " steps";
    if (step % scene.output.observe_every == 0 || !reason.empty()) observe(step);
    if (t >= next_frame * (1 - 1e-12) || !reason.empty()) {
      write_frame(step);
      // An interval shorter than a step: one frame a step, the frames passed over skipped at once (not
      // one by one: 1e-300 s would loop for ever).
      const double fi = scene.output.frame_interval, now = t * (1 + 1e-12);
      next_frame += std::max(0.0, std::floor((now - next_frame) / fi)) * fi;  // (0 for an interval of a step or more)
      while (next_frame <= now) {
        const double after = next_frame + fi;
        next_frame = after > next_frame ? after : t * (1 + 2e-12);
      }
    }
    progress.tick([&] {
      std::ostringstream s;
      s.precision(3);
      const double el = progress.elapsed();
      s << "t = " << t << " s, step " << step << ", " << static_cast<double>(step - first_step) / std::max(el, 1e-9)
        << " steps/s, " << broken.size() << " beams broken, ETA "
        << (stop.t_max - t) / std::max(t - first_t, 1e-30) * el << " s (at most)";
      return s.str();
    });
    if (!reason.empty()) {
      summary.stop_reason = reason;
      break;
    }
    if (io::Checkpoints* ck = continuation.checkpoints) {
      if (ck->due(step)) ck->write(step, t, visit_state);
      ck->stop_if_signalled(step, t, visit_state);
    }
  }
  if (writer) writer->finish();
  summary.phases = step_phases.times();
  summary.steps = step;
  summary.time = integrator.t();
  summary.broken = static_cast<std::int64_t>(broken.size());
  summary.wall_seconds = progress.elapsed();
  return summary;
}

}  // namespace frac::dem
