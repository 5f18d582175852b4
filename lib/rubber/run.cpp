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
#include "rubber/lattice.hpp"
#include "rubber/three_body_residual.hpp"

namespace frac::rubber {

RubberSystem build_rubber(const mesh::NodeMesh& mesh, const RubberSetup& su, std::uint64_t seed, int threads) try {
  const RubberScene& sc = su.scene;
  RubberSystem sys;
  ModelOptions mo;
  mo.law = su.law;
  mo.node_mass = su.node_mass;
  mo.damping = sc.damping ? sc.damping_kind : DampingKind::none;
  mo.beta = sc.beta;
  mo.damping_onset = sc.damping_onset;
  mo.failure = sc.failure == "freeze" ? Failure::freeze : Failure::paper;
  mo.break_extra = sc.irreversible ? sc.break_widths * sc.cutoff_width : std::numeric_limits<double>::infinity();
  mo.threads = threads;
  Lattice lattice = build_lattice(mesh, sc.periodic_x, sc.periodic_y);
  if (sc.three_body_residual > 0) mo.residual = three_body_residual(su.law, lattice, su.F, sc.three_body_residual);
  sys.model = std::make_unique<Model>(std::move(lattice), mo);
  Model& model = *sys.model;
  const Lattice& L = model.lattice();
  const std::size_t n = L.n;
  model.set_box(su.F);
  sys.path = std::make_unique<CrackPath>(mesh, L);

  // Homogeneous pre-stretch about the origin of the mesh: the sheet starts in equilibrium. With
  // loading.ramp_time, it starts at λy = loading.ramp_from_y instead, moving at the homogeneous stretch rate
  // (v_y = λ̇y r_y, so no wave starts from the grips), which the clamped rows keep until ramp_time.
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

  // The seed crack, along the mesh's crack line from the left edge; the bulk off the line tougher.
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

  // A localized pulse: Gaussian displacement (standard deviation pulse.width) of the lines across the
  // direction of propagation, along it (longitudinal) or across it (shear).
  if (sc.pulse_amplitude > 0) {
    const bool along_x = sc.pulse_direction == "x";
    const auto& s = along_x ? L.rx : L.ry;
    const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
    const double s0 = *lo + sc.pulse_position * (*hi - *lo);
    const bool disp_x = along_x == (sc.pulse_kind == "longitudinal");
    for (std::size_t i = 0; i < n; ++i) {
      const double z = (s[i] - s0) / sc.pulse_width;
      const double u = sc.pulse_amplitude * std::exp(-0.5 * z * z);
      sys.q0[disp_x ? i : n + i] += u;
    }
  }

  // Clamps: rows j < k and j >= ny - k (top and bottom), columns likewise (index = j nx + i).
  std::vector<std::size_t> clamped;
  const auto nx = static_cast<std::size_t>(mesh.nx), ny = static_cast<std::size_t>(mesh.ny);
  const auto kr = static_cast<std::size_t>(sc.clamp_rows), kc = static_cast<std::size_t>(sc.clamp_columns);
  if ((kr > 0 || kc > 0) && nx * ny != n) throw InputError("clamps need an nx x ny mesh");
  for (std::size_t j = 0; j < ny && (kr > 0 || kc > 0); ++j)
    for (std::size_t i = 0; i < nx; ++i)
      if (j < kr || j + kr >= ny || i < kc || i + kc >= nx) clamped.push_back(j * nx + i);
  if (!clamped.empty()) {
    if (sc.ramp_time > 0) model.clamp(clamped, sys.q0, sys.v0, sc.ramp_time);
    else model.clamp(clamped, sys.q0);
  }

  // Thermal noise: uniform velocities with zero mean over the free nodes.
  if (sc.noise > 0) {
    Rng rng(seed);
    std::vector<std::uint8_t> fixed(n, 0);
    for (std::size_t i : clamped) fixed[i] = 1;
    std::size_t free = 0;
    double mean[2] = {0, 0};
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 2; ++c) {
        const double v = rng.uniform(-sc.noise, sc.noise);
        if (fixed[i]) continue;
        sys.v0[static_cast<std::size_t>(c) * n + i] += v;
        mean[c] += v;
      }
    for (std::size_t i = 0; i < n; ++i) free += fixed[i] ? 0 : 1;
    for (std::size_t i = 0; i < n && free > 0; ++i)
      if (!fixed[i])
        for (int c = 0; c < 2; ++c) sys.v0[static_cast<std::size_t>(c) * n + i] -= mean[c] / static_cast<double>(free);
  }

  // Tip kick: the two nodes of the first intact bond ahead of the tip move apart in y.
  if (sc.tip_kick > 0) {
    const std::size_t k = sys.path->next_intact(model, sys.q0);
    if (k < sys.path->size()) {
      const std::size_t b = sys.path->bond(k), i = b / 3, j = L.bond_other(b);
      const double yi = L.ry[i] > sys.path->line_y() ? 1.0 : -1.0;
      sys.v0[n + i] += yi * sc.tip_kick;
      sys.v0[n + j] -= yi * sc.tip_kick;
    }
  }
  for (std::size_t i : clamped) {
    sys.v0[i] = 0;
    sys.v0[n + i] = rate_y * L.ry[i];
  }
  return sys;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the rubber lattice of " + std::to_string(mesh.nodes()) + " nodes");
}

namespace {

// Least-squares slope of (t, x) over a ring buffer, in a fixed order.
struct SpeedFit {
  std::vector<double> t, x;
  std::size_t head = 0, count = 0;
  explicit SpeedFit(std::size_t capacity) : t(std::max<std::size_t>(capacity, 2)), x(t.size()) {}
  void add(double tt, double xx) {
    t[head] = tt;
    x[head] = xx;
    head = (head + 1) % t.size();
    count = std::min(count + 1, t.size());
  }
  double slope() const {
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
};

}  // namespace

RubberSummary run_rubber(RubberSystem& sys, const RubberSetup& su, io::RunWriter* writer, Progress& progress,
                         const io::Continuation& continuation) {
  const RubberScene& sc = su.scene;
  Model& model = *sys.model;
  const Lattice& L = model.lattice();
  const std::size_t n = L.n;
  const CrackPath& path = *sys.path;
  RubberSummary sum;
  sum.dt = su.dt;
  const double dt = su.dt;

  auto integ = dynamics::make_integrator(sc.integrator);
  integ->start(model, 0.0, dt, sys.q0, sys.v0);

  // Everything the loop needs, allocated before it.
  const std::size_t mesh_bonds = L.bond_id.size();
  io::BodyFrame frame;
  frame.position.resize(2 * n);
  frame.velocity.resize(2 * n);
  frame.intact.resize(mesh_bonds);
  frame.strain.resize(mesh_bonds);
  std::vector<std::size_t> events;
  events.reserve(L.bonds());
  const auto window = static_cast<std::size_t>(
      std::min(1e6, std::ceil(sc.speed_window / (static_cast<double>(sc.observe_every) * dt)) + 1));
  SpeedFit fit(window);
  const std::string k_kinetic = "kinetic_energy", k_potential = "potential_energy", k_total = "total_energy",
                    k_events = "bonds_past_cutoff", k_tip = "crack_tip_x", k_tip_ref = "crack_tip_reference_x",
                    k_speed = "crack_tip_speed", k_tough = "toughened_bonds", k_drive = "drive_energy",
                    k_frozen = "frozen_energy";
  const bool freeze = model.options().failure == Failure::freeze;

  auto write_frame = [&](std::int64_t step) {
    if (!writer) return;
    const auto q = integ->q();
    const auto v = integ->v();
    for (std::size_t i = 0; i < n; ++i) {
      frame.position[2 * i] = q[i];
      frame.position[2 * i + 1] = q[n + i];
      frame.velocity[2 * i] = v[i];
      frame.velocity[2 * i + 1] = v[n + i];
    }
    for (std::size_t k = 0; k < mesh_bonds; ++k) {
      const auto b = static_cast<std::size_t>(L.bond_id[k]);
      frame.intact[k] = model.holds(b, q) ? 1 : 0;
      frame.strain[k] = model.bond_length(b, q) / L.spacing - 1;
    }
    frame.step = step;
    frame.time = integ->t();
    writer->write_frame(frame);
  };

  CrackPath::Tip tip = path.tip(model, integ->q());
  sum.tip_start = tip;
  std::int64_t last_observed = -1;
  // The clamped rows move (and work on the sheet) until loading.ramp_time.
  const double grips_stop = sc.ramp_time > 0 ? sc.ramp_time : 0.0;
  const dynamics::RunawayGuard runaway(integ->q(), n, "node");
  auto observe = [&](std::int64_t step) {
    last_observed = step;
    const auto q = integ->q();
    runaway.check(q, step, integ->t());
    const double ke = model.kinetic_energy(integ->v());
    const Model::Energy energy = model.potential_energy(q);
    const double pe = energy.total();
    tip = path.tip(model, q);
    // The speed is fitted to λx × reference x of the tip: the lab position of the crack in the far
    // field (the tip's own nodes may fly off as debris).
    if (tip.found) fit.add(integ->t(), su.F(0, 0) * tip.reference_x);
    sum.tip_speed = fit.slope();
    sum.energy_end = ke + pe;
    if (step == 0) sum.energy_start = ke + pe;
    if (!sum.energy_conserved_set && integ->t() >= grips_stop) {
      sum.energy_conserved_set = true;
      sum.energy_conserved = ke + pe;
      sum.energy_conserved_time = integ->t();
      sum.drive_energy_conserved = sum.drive_energy;
    }
    if (!writer) return;
    const double t = integ->t();
    writer->observe(k_kinetic, step, t, ke, "J");
    writer->observe(k_potential, step, t, pe, "J");
    writer->observe(k_total, step, t, ke + pe, "J");
    writer->observe(k_events, step, t, static_cast<double>(sum.events), "1");
    writer->observe(k_tip, step, t, tip.found ? tip.lab_x : std::nan(""), "m");
    writer->observe(k_tip_ref, step, t, tip.found ? tip.reference_x : std::nan(""), "m");
    writer->observe(k_speed, step, t, sum.tip_speed, "m s-1");
    if (sc.toughening) writer->observe(k_tough, step, t, static_cast<double>(sum.toughened), "1");
    if (sys.drive) writer->observe(k_drive, step, t, sum.drive_energy, "J");
    if (freeze) writer->observe(k_frozen, step, t, energy.frozen, "J");
  };

  auto collect_events = [&](std::int64_t step) {
    if (model.pending_events() == 0 && model.pending_breaks() == 0) return;
    events.clear();
    model.take_events(events);
    sum.events += events.size();
    sum.irreversible += static_cast<std::size_t>(model.pending_breaks());
    model.clear_breaks();
    if (!writer) return;
    for (std::size_t b : events) {
      const std::int64_t k = L.mesh_bond[b];
      if (k >= 0) writer->record_break({step, integ->t(), k, 1});
    }
  };

  std::int64_t step = 0;
  double next_frame = sc.frame_interval > 0 ? sc.frame_interval : 1e300;
  // Everything the loop carries from step to step: what a checkpoint saves and a continuation loads.
  const auto visit_state = [&](StateArchive& a) {
    integ->visit_state(a);
    model.visit_state(a);
    if (sys.drive) sys.drive->visit_state(a);
    StateArchive::Scope scope(a, "run");
    a.value("step", step);
    a.value("next_frame", next_frame);
    a.value("last_observed", last_observed);
    a.value("last_frame_step", frame.step);
    a.value("events", sum.events);
    a.value("irreversible", sum.irreversible);
    a.value("toughened", sum.toughened);
    a.value("driven", sum.driven);
    a.value("drive_energy", sum.drive_energy);
    a.value("energy_start", sum.energy_start);
    a.value("energy_end", sum.energy_end);
    a.value("energy_conserved_set", sum.energy_conserved_set);
    a.value("energy_conserved", sum.energy_conserved);
    a.value("energy_conserved_time", sum.energy_conserved_time);
    a.value("drive_energy_conserved", sum.drive_energy_conserved);
    a.value("tip_speed", sum.tip_speed);
    for (auto [name, t] : {std::pair{"tip", &tip}, std::pair{"tip_start", &sum.tip_start}}) {
      StateArchive::Scope tip_scope(a, name);
      a.value("found", t->found);
      a.value("bond", t->bond);
      a.value("reference_x", t->reference_x);
      a.value("lab_x", t->lab_x);
      a.value("broken", t->broken);
    }
    StateArchive::Scope fit_scope(a, "speed_fit");
    a.array("t", fit.t, fit.t.size());
    a.array("x", fit.x, fit.x.size());
    a.value("head", fit.head);
    a.value("count", fit.count);
    if (a.loading() && (fit.head >= fit.t.size() || fit.count > fit.t.size()))
      a.refuse("head", "outside the speed window");
  };
  if (continuation.resume) {
    visit_state(*continuation.resume);
  } else {
    observe(0);
    write_frame(0);
  }
  const std::int64_t first_step = step;  // (of this process: the time loop's rate counts from here)
  std::optional<DeferSignals> defer;
  if (continuation.checkpoints) defer.emplace();
  const std::string stop_tip = "the crack tip reached stop.tip_margin from the far edge";
  std::string reason = "stop.t_max reached";
  const std::function<std::string()> line = [&] {
    std::ostringstream s;
    s.precision(4);
    s << "t = " << integ->t() << " s (" << std::lround(100 * integ->t() / sc.t_max) << "%), step " << step;
    if (tip.found)
      s << ", tip at x = " << tip.lab_x << " m (" << (tip.reference_x - sum.tip_start.reference_x) / L.spacing
        << " spacings), v = " << sum.tip_speed << " m/s";
    s << ", " << sum.events << " bonds past u_c";
    return s.str();
  };
  const double t_end = sc.t_max - 0.5 * dt;
  bool stop = false;
  const auto loop_start = std::chrono::steady_clock::now();
  while (!stop) {
    if (integ->t() >= t_end) break;
    if (step >= sc.max_steps) {
      reason = "stop.max_steps reached";
      break;
    }
    integ->step(model);
    ++step;
    if (model.nonfinite() > 0) [[unlikely]] {
      std::ostringstream msg;
      msg.precision(6);
      msg << "non-finite force at step " << step << " (t = " << integ->t()
          << " s): " << model.diagnose_nonfinite(integ->q(), integ->a())
          << "; the time step may be too large for this scene";
      throw RuntimeError(msg.str());
    }
    if (sys.drive && !sys.drive->finished()) {
      double change = 0;
      sum.driven += sys.drive->cut(model, integ->t(), integ->q(), change);
      sum.drive_energy += change;
    }
    collect_events(step);
    if (sc.toughening && step % sc.toughening_every == 0)
      sum.toughened += model.toughen(integ->q(), sc.toughening_trigger, sc.toughening_cutoff);
    const bool at_frame = integ->t() >= next_frame - 0.5 * dt;
    if (step % sc.observe_every == 0 || at_frame) {
      observe(step);
      if (sc.tip_margin > 0 && tip.found && tip.reference_x > path.x_max() - sc.tip_margin) {
        reason = stop_tip;
        stop = true;
      }
    }
    if (at_frame) {
      write_frame(step);
      next_frame += sc.frame_interval;
    }
    progress.tick(line);
    if (io::Checkpoints* ck = continuation.checkpoints; ck && !stop) {
      if (ck->due(step)) ck->write(step, integ->t(), visit_state);
      ck->stop_if_signalled(step, integ->t(), visit_state);
    }
  }
  sum.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  sum.nodes = n;
  sum.loop_steps = step - first_step;
  // The final state: always an observation and a frame.
  if (last_observed != step) observe(step);
  if (!writer || writer->frames() == 0 || frame.step != step) write_frame(step);
  sum.steps = step;
  sum.time = integ->t();
  sum.stop_reason = reason;
  sum.tip = tip;
  sum.wall_seconds = progress.elapsed();
  if (writer) writer->finish();
  return sum;
}

}  // namespace frac::rubber
