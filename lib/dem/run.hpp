#pragma once
// A DEM run: integrate the model under its loading until the stop rule, break beams after each step,
// keep the energy ledger, write decimated frames and observables, stop at once on a non-finite value
// naming the step, the cell and the term.
#include <cstdint>
#include <string>
#include <vector>

#include "core/phases.hpp"
#include "core/progress.hpp"
#include "dem/loading.hpp"
#include "dem/model.hpp"
#include "dem/scene.hpp"
#include "io/checkpoint.hpp"
#include "io/run_io.hpp"

namespace frac::dem {

struct RunSummary {
  std::int64_t steps = 0;
  double time = 0;            // s
  double dt = 0;              // s
  std::int64_t broken = 0;    // beams broken during the run
  std::string stop_reason;    // "t_max", "max_steps", "no breaking for N steps"
  double energy_error = 0;    // max |E_balance − E_balance(0)| over the run, J
  double energy_scale = 0;    // J: the larger of the initial energy and the boundary work
  double wall_seconds = 0;
  int start_evaluations = 0;  // force evaluations of an exact gear5 start (0 for the usual start)
  int checkpoints = 0;          // written by this process
  double checkpoint_seconds = 0;  // wall time spent writing them
  std::vector<PhaseTime> phases;  // the time of each phase of the steps (core/phases)
};

struct Ledger {
  std::vector<double> law_work;  // work done by each contact law on the bodies (Model::contact_laws' order), J
  double boundary = 0;           // work done by the moving boundaries, J
  double broken_energy = 0;      // elastic energy removed with broken beams, J
};


// Runs `model` from (q0, v0); writes frames and observables through `writer` (frames every
// plan.frame_interval and the final state; observables every plan.observe_every steps). The integrator
// starts as scene.integrator.start says; `start_tau` is the time scale of an exact start
// (dynamics::taylor_derivatives: about 0.1/ω_max). With checkpoints, one is written when due and when a stop
// signal arrives (then Interrupted is thrown).
// The initial state (q0, v0) is released once the integrator has started from it (memory).
RunSummary run_dem(Model& model, dynamics::Integrator& integrator, const DemScene& scene, const LoadingSetup& setup,
                   std::vector<double> q0, std::vector<double> v0, double dt, io::RunWriter* writer,
                   Progress& progress, double start_tau, const io::Continuation& continuation = {});

}  // namespace frac::dem
