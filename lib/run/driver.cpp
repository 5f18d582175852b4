#include "run/driver.hpp"

#include <chrono>
#include <optional>

#include "core/signals.hpp"
#include "io/checkpoint.hpp"
#include "io/run_io.hpp"

namespace frac::run {
namespace {

// The loop's output: the frame datasets declared to the writer, frames and observations written.
class Output {
 public:
  Output(Engine& engine, io::RunWriter* writer) : engine_(engine), writer_(writer) {
    if (writer_ && !writer_->trajectory_started()) declare_frames(engine_, *writer_);
  }

  void observe(std::int64_t step) {
    last_observed = step;
    engine_.measure(step);
    if (!writer_) return;
    const double t = engine_.integrator().t();
    for (const Observable& o : engine_.observables()) writer_->observe(o.name, step, t, o.value(), o.unit);
  }

  void frame(std::int64_t step) {
    last_frame = step;
    if (!writer_) return;
    const double t = engine_.integrator().t();
    // (Its buffers only while it is written: memory between frames, when the neighbour list is rebuilt.)
    std::vector<double> values;
    std::vector<std::uint8_t> flags;
    const auto& datasets = engine_.frame_datasets();
    for (std::size_t k = 0; k < datasets.size(); ++k) {
      const FrameDataset& d = datasets[k];
      if (d.flags) {
        flags.resize(d.items * d.components);
        d.fill_flags(flags);
        writer_->append(k, step, t, std::span<const std::uint8_t>(flags));
      } else {
        values.resize(d.items * d.components);
        d.fill(values);
        writer_->append(k, step, t, std::span<const double>(values));
      }
    }
  }

  void record(std::int64_t step, const std::vector<Event>& events) {
    if (!writer_) return;
    for (const Event& e : events) writer_->record_break({step, engine_.integrator().t(), e.index, e.mode});
  }

  std::int64_t last_observed = -1, last_frame = -1;

 private:
  Engine& engine_;
  io::RunWriter* writer_;
};

}  // namespace

void declare_frames(const Engine& engine, io::RunWriter& writer) {
  std::vector<io::SeriesSpec> specs;
  for (const FrameDataset& d : engine.frame_datasets()) {
    std::vector<hsize_t> dims{d.items};
    if (d.components > 1) dims.push_back(d.components);
    specs.push_back({d.group, d.name, dims, d.unit, d.flags});
  }
  writer.declare_trajectory(std::move(specs));
}

Outcome drive(Engine& engine, io::RunWriter* writer, Progress& progress, const io::Continuation& continuation) {
  Outcome out;
  Output output(engine, writer);
  engine.start();
  std::int64_t step = 0;
  // Everything a checkpoint saves and a continuation loads: the engine's state, and the loop's counters.
  const auto visit_state = [&](StateArchive& a) {
    engine.state().visit(a);
    StateArchive::Scope scope(a, "run");
    a.value("step", step);
    a.value("last_observed", output.last_observed);
    a.value("last_frame_step", output.last_frame);
  };
  if (continuation.resume) {
    visit_state(*continuation.resume);
  } else {
    output.observe(0);
    output.frame(0);
  }
  const std::int64_t first_step = step;
  const double first_t = engine.integrator().t();
  std::optional<DeferSignals> defer;
  if (continuation.checkpoints) defer.emplace();
  Phases phases = engine.step_phases();
  const std::size_t team = engine.team_size();
  std::vector<Event> events;
  const auto loop_start = std::chrono::steady_clock::now();
  std::string reason = engine.stop_reason(step);
  while (reason.empty()) {
    engine.bind_step();
    phases.run(team);
    ++step;
    events.clear();
    engine.after_step(step, events);
    output.record(step, events);
    const bool frame = engine.frame_due();
    if (engine.observe_due(step, frame)) output.observe(step);
    if (frame) {
      output.frame(step);
      engine.frame_written();
    }
    reason = engine.stop_reason(step);
    progress.tick([&] { return engine.progress_line(step, first_step, first_t, progress.elapsed()); });
    if (io::Checkpoints* ck = continuation.checkpoints; ck && reason.empty()) {
      const double t = engine.integrator().t();
      if (ck->due(step)) ck->write(step, t, visit_state);
      ck->stop_if_signalled(step, t, visit_state);
    }
  }
  out.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  out.loop_steps = step - first_step;
  // The final state: always an observation and a frame.
  if (output.last_observed != step) output.observe(step);
  if (output.last_frame != step) output.frame(step);
  if (writer) writer->finish();
  out.steps = step;
  out.time = engine.integrator().t();
  out.stop_reason = reason;
  out.wall_seconds = progress.elapsed();
  out.phases = phases.times();
  return out;
}

Outcome drive(Engine& engine, Progress& progress) { return drive(engine, nullptr, progress, io::Continuation{}); }

}  // namespace frac::run
