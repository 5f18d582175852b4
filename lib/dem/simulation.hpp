#pragma once
// One DEM simulation from a mesh and a resolved scene: the model, the loading, the time step and the
// integrator, ready to run (its engine for run/driver). What dem-run (and tests, benchmarks) build.
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "dem/loading.hpp"
#include "dem/model.hpp"
#include "dem/run.hpp"
#include "dem/scene.hpp"
#include "dem/timestep.hpp"

namespace frac::dem {

struct Simulation {
  // (`mesh` must outlive the simulation.)
  Simulation(const mesh::CellMesh& mesh, const DemScene& scene);
  const mesh::CellMesh* cell_mesh;
  DemScene scene;
  Model model;
  LoadingSetup setup;
  TimeStep time_step;
  std::unique_ptr<dynamics::Integrator> integrator;
  std::vector<double> q0, v0;
  // The run of this simulation, once: q0 and v0 move into it (and are empty after it).
  DemRun engine() {
    return DemRun(model, *integrator, *cell_mesh, scene, setup, std::move(q0), std::move(v0), time_step.dt,
                  start_tau());
  }
  // Runs it without output (tests, benchmarks).
  RunSummary run(Progress& progress) {
    DemRun e = engine();
    return e.summary(run::drive(e, progress));
  }
  // Time scale of an exact start: 0.1 of the fastest motion (ω_max, or the damping rate γ_max).
  double start_tau() const { return 0.1 / std::max(time_step.omega_max, time_step.gamma_max); }
};

// The initial kick of an explosion, pulse or impact (validation B1-B3 of the physics note): how many
// cells move, their kinetic energy (J), their mean speed (m/s), and |Σ m v| / Σ m |v| (0 to round-off).
struct KickReport {
  std::size_t cells = 0;
  double kinetic_energy = 0, mean_speed = 0, momentum_over_scale = 0;
};
KickReport kick_report(const Simulation& sim);

}  // namespace frac::dem
