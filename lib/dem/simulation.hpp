#pragma once
// One DEM simulation from a mesh and a resolved scene: the model, the loading, the time step and the
// integrator, ready to run. What dem-run (and tests, benchmarks) build before calling run_dem.
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
  // Runs the simulation, once: q0 and v0 move into the run (and are empty after it).
  RunSummary run(io::RunWriter* writer, Progress& progress, const io::Continuation& continuation = {}) {
    return run_dem(model, *integrator, scene, setup, std::move(q0), std::move(v0), time_step.dt, writer, progress,
                   start_tau(), continuation);
  }
  // Time scale of an exact start: 0.1 of the fastest motion (ω_max, or the damping rate γ_max).
  double start_tau() const {
    return 0.1 / std::max(time_step.omega_max, time_step.gamma_max);
  }
};

// The initial kick of an explosion, pulse or impact (validation B1-B3 of the physics note): how many
// cells move, their kinetic energy (J), their mean speed (m/s), and |Σ m v| / Σ m |v| (0 to round-off).
struct KickReport {
  std::size_t cells = 0;
  double kinetic_energy = 0, mean_speed = 0, momentum_over_scale = 0;
};
KickReport kick_report(const Simulation& sim);

}  // namespace frac::dem
