#pragma once
// A DEM run as an engine of the run driver (run/engine): the model's step with the breaking pass after it, the
// energy ledger (the power of each contact law and of the moving boundaries integrated between evaluations, the
// energy of broken beams), the observables and frame datasets as tables, the stop rule (t_max, max_steps, steps
// without a break) and the output plan, a non-finite value stopping the run at once, naming the step, the cell
// and the term.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/phases.hpp"
#include "core/progress.hpp"
#include "core/state_registry.hpp"
#include "dem/loading.hpp"
#include "dem/model.hpp"
#include "dem/scene.hpp"
#include "dynamics/runaway.hpp"
#include "run/driver.hpp"
#include "run/engine.hpp"

namespace frac::dem {

struct RunSummary {
  std::int64_t steps = 0;
  double time = 0;          // s
  double dt = 0;            // s
  std::int64_t broken = 0;  // beams broken during the run
  std::string stop_reason;  // "t_max", "max_steps", "no breaking for N steps"
  double energy_error = 0;  // max |E_balance − E_balance(0)| over the run, J
  double energy_scale = 0;  // J: the larger of the initial energy and the boundary work
  double wall_seconds = 0;
  int start_evaluations = 0;      // force evaluations of an exact gear5 start (0 for the usual start)
  int checkpoints = 0;            // written by this process
  double checkpoint_seconds = 0;  // wall time spent writing them
  std::vector<PhaseTime> phases;  // the time of each phase of the steps (core/phases)
};

struct Ledger {
  std::vector<double> law_work;  // work done by each contact law on the bodies (Model::contact_laws' order), J
  double boundary = 0;           // work done by the moving boundaries, J
  double broken_energy = 0;      // elastic energy removed with broken beams, J
};

class DemRun final : public run::Engine {
 public:
  // A run of `model` from (q0, v0), released once the integrator has started from them (memory); the
  // integrator starts as scene.integrator.start says, `start_tau` the time scale of an exact start
  // (dynamics::taylor_derivatives: about 0.1/ω_max). `mesh`: the model's.
  DemRun(Model& model, dynamics::Integrator& integrator, const mesh::CellMesh& mesh, const DemScene& scene,
         const LoadingSetup& setup, std::vector<double> q0, std::vector<double> v0, double dt, double start_tau);
  DemRun(const DemRun&) = delete;  // (its tables and state call it where it is)
  DemRun& operator=(const DemRun&) = delete;

  void start() override;
  const dynamics::Integrator& integrator() const override { return integrator_; }
  Phases step_phases() override;
  void bind_step() override;
  std::size_t team_size() const override { return integrator_.team_for(model_); }
  void after_step(std::int64_t step, std::vector<run::Event>& events) override;
  std::string stop_reason(std::int64_t step) const override;
  bool frame_due() const override;
  void frame_written() override;
  bool observe_due(std::int64_t step, bool) const override { return step % scene_.output.observe_every == 0; }
  void measure(std::int64_t step) override;
  const std::vector<run::Observable>& observables() const override { return observables_; }
  const std::vector<run::FrameDataset>& frame_datasets() const override { return frames_; }
  run::RunBodies bodies() const override;
  const StateRegistry& state() const override { return state_; }
  std::vector<std::pair<std::string, std::int64_t>> run_attributes() const override {
    return {{"start_evaluations", start_evaluations_}};
  }
  std::string progress_line(std::int64_t step, std::int64_t first_step, double first_t, double elapsed) const override;

  // The run's summary, from the driver's outcome.
  RunSummary summary(const run::Outcome& outcome) const;

 private:
  void declare_state();
  void make_observables();
  void make_frames();
  double law_work(const std::string& name) const;  // the work done by the law `name` (0 when it is off)
  Model& model_;
  dynamics::Integrator& integrator_;
  const mesh::CellMesh& mesh_;
  const DemScene& scene_;
  const LoadingSetup& setup_;
  std::vector<double> q0_, v0_;
  double dt_, start_tau_;
  std::optional<dynamics::RunawayGuard> runaway_;
  Ledger ledger_;
  std::vector<BeamBreak> broken_;
  std::vector<double> previous_power_;
  double previous_boundary_power_ = 0;
  double e0_ = 0;  // the energy balance at step 0
  double energy_error_ = 0, energy_scale_ = 0;
  int start_evaluations_ = 0;
  double next_frame_ = 0;
  std::int64_t last_break_step_ = -1;
  std::size_t broken_before_ = 0;  // broken_ before the step under way
  struct Measured {                // what an observation measured, for the table's rows
    std::array<double, 2> kinetic{};
    double beam_energy = 0, balance = 0;
  } measured_;
  StateRegistry state_;
  std::vector<run::Observable> observables_;
  std::vector<run::FrameDataset> frames_;
};

}  // namespace frac::dem
