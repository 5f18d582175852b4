#pragma once
// A rubber-run: the model built from a mesh and a prepared scene, its initial state (pre-stretch,
// clamps, seed crack, pulse, noise, tip kick), the time loop with the shared integrator, and what it
// records: frames, observables (energies, bonds past u_c, crack tip and its speed) and bond-break
// events, as an engine of the run driver (run/driver). The loop allocates nothing.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/phases.hpp"
#include "core/progress.hpp"
#include "core/state_registry.hpp"
#include "dynamics/integrator.hpp"
#include "dynamics/runaway.hpp"
#include "mesh/node_mesh.hpp"
#include "rubber/crack.hpp"
#include "rubber/crack_drive.hpp"
#include "rubber/model.hpp"
#include "rubber/setup.hpp"
#include "run/driver.hpp"
#include "run/engine.hpp"

namespace frac::rubber {

// The model and its initial state for a scene, before any step.
struct RubberSystem {
  std::unique_ptr<Model> model;
  std::unique_ptr<CrackPath> path;
  std::vector<double> q0, v0;
  std::size_t seeded = 0;             // crossing bonds cut by crack.seed_length (besides the mesh's notch)
  std::unique_ptr<CrackDrive> drive;  // the driven seed (crack.drive_speed), null when off
};
RubberSystem build_rubber(const mesh::NodeMesh& mesh, const RubberSetup& setup, std::uint64_t seed, int threads);

struct RubberSummary {
  long long steps = 0;
  double time = 0, dt = 0;
  std::string stop_reason;
  std::size_t events = 0;                   // bonds that went past their cut-off (once each)
  std::size_t irreversible = 0;             // bonds removed by irreversible breaking
  std::size_t toughened = 0;                // bonds whose cut-off was raised
  std::size_t driven = 0;                   // bonds the knife of the driven seed removed
  double drive_energy = 0;                  // J, change of the potential energy by those cuts (the knife's work)
  CrackPath::Tip tip_start, tip;            // crack tip at the start and at the end
  double tip_speed = 0;                     // m/s, last fitted speed of λx × reference tip x over output.speed_window
  double energy_start = 0, energy_end = 0;  // J, kinetic + potential
  // The energy when the clamped rows stop doing work (t = 0, or the first observation from loading.ramp_time
  // on), and the knife's work by then: undamped, energy_end - energy_conserved equals the knife's work since.
  bool energy_conserved_set = false;
  double energy_conserved = 0, energy_conserved_time = 0, drive_energy_conserved = 0;
  double wall_seconds = 0;
  double loop_seconds = 0;   // wall time of the time loop alone (steps, events, observations)
  long long loop_steps = 0;  // steps of that loop (fewer than `steps` in a run continued from a checkpoint)
  double ns_per_node_step() const {
    return loop_steps > 0 && nodes > 0
               ? 1e9 * loop_seconds / (static_cast<double>(loop_steps) * static_cast<double>(nodes))
               : 0;
  }
  std::size_t nodes = 0;
  int checkpoints = 0;            // written by this process
  double checkpoint_seconds = 0;  // wall time spent writing them
  std::vector<PhaseTime> phases;  // the time of each phase of the steps (core/phases)
};

// Least-squares slope of (t, x) over a ring buffer, in a fixed order: the crack tip's speed.
struct SpeedFit {
  std::vector<double> t, x;
  std::size_t head = 0, count = 0;
  explicit SpeedFit(std::size_t capacity) : t(std::max<std::size_t>(capacity, 2)), x(t.size()) {}
  void add(double tt, double xx);
  double slope() const;
};

// A rubber run as an engine of the run driver (run/engine): the lattice's step, then its events (bonds past
// u_c, irreversible breaks), the driven seed's knife and the toughening of the crack faces; the observables
// (energies, the crack tip and its speed) and frame datasets as tables; the stop rule (t_max, max_steps, the tip
// near the far edge) and the output plan.
class RubberRun final : public run::Engine {
 public:
  RubberRun(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh);
  RubberRun(const RubberRun&) = delete;  // (its tables and state call it where it is)
  RubberRun& operator=(const RubberRun&) = delete;

  void start() override;
  const dynamics::Integrator& integrator() const override { return *integ_; }
  Phases step_phases() override { return integ_->step_phases(model_); }
  void bind_step() override { integ_->begin_step(model_); }
  std::size_t team_size() const override { return integ_->team_for(model_); }
  void after_step(std::int64_t step, std::vector<run::Event>& events) override;
  std::string stop_reason(std::int64_t step) const override;
  bool frame_due() const override { return integ_->t() >= next_frame_ - 0.5 * setup_.dt; }
  void frame_written() override { next_frame_ += setup_.scene.frame_interval; }
  bool observe_due(std::int64_t step, bool frame) const override {
    return step % setup_.scene.observe_every == 0 || frame;
  }
  void measure(std::int64_t step) override;
  const std::vector<run::Observable>& observables() const override { return observables_; }
  const std::vector<run::FrameDataset>& frame_datasets() const override { return frames_; }
  run::RunBodies bodies() const override;
  const StateRegistry& state() const override { return state_; }
  std::string progress_line(std::int64_t step, std::int64_t first_step, double first_t, double elapsed) const override;

  // The run's summary, from the driver's outcome.
  RubberSummary summary(const run::Outcome& outcome) const;

 private:
  void declare_state();
  void make_observables();
  void make_frames();
  RubberSystem& sys_;
  const RubberSetup& setup_;
  const mesh::NodeMesh& mesh_;
  Model& model_;
  std::unique_ptr<dynamics::Integrator> integ_;
  std::optional<dynamics::RunawayGuard> runaway_;
  RubberSummary sum_;
  CrackPath::Tip tip_;
  SpeedFit fit_;
  double next_frame_;
  bool tip_stop_ = false;  // the last observation found the tip past stop.tip_margin
  Model::Energy energy_;
  double kinetic_ = 0;
  std::vector<std::size_t> events_;
  StateRegistry state_;
  std::vector<run::Observable> observables_;
  std::vector<run::FrameDataset> frames_;
};

// Runs to the stop rule, without output (tests, benchmarks).
RubberSummary run_rubber(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh,
                         Progress& progress);

}  // namespace frac::rubber
