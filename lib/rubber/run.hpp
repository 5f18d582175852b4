#pragma once
// A rubber-run: the model built from a mesh and a prepared scene, its initial state (pre-stretch,
// clamps, seed crack, pulse, noise, tip kick), the time loop with the shared integrator, and what it
// records: frames, observables (energies, bonds past u_c, crack tip and its speed) and bond-break
// events, through io::RunWriter. The loop allocates nothing; progress goes to a core::Progress.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "dynamics/integrator.hpp"
#include "io/checkpoint.hpp"
#include "io/run_io.hpp"
#include "mesh/node_mesh.hpp"
#include "rubber/crack.hpp"
#include "rubber/crack_drive.hpp"
#include "rubber/model.hpp"
#include "rubber/setup.hpp"

namespace frac::rubber {

// The model and its initial state for a scene, before any step.
struct RubberSystem {
  std::unique_ptr<Model> model;
  std::unique_ptr<CrackPath> path;
  std::vector<double> q0, v0;
  std::size_t seeded = 0;  // crossing bonds cut by crack.seed_length (besides the mesh's notch)
  std::unique_ptr<CrackDrive> drive;  // the driven seed (crack.drive_speed), null when off
};
RubberSystem build_rubber(const mesh::NodeMesh& mesh, const RubberSetup& setup, std::uint64_t seed, int threads);

struct RubberSummary {
  long long steps = 0;
  double time = 0, dt = 0;
  std::string stop_reason;
  std::size_t events = 0;           // bonds that went past their cut-off (once each)
  std::size_t irreversible = 0;     // bonds removed by irreversible breaking
  std::size_t toughened = 0;        // bonds whose cut-off was raised
  std::size_t driven = 0;           // bonds the knife of the driven seed removed
  double drive_energy = 0;          // J, change of the potential energy by those cuts (the knife's work)
  CrackPath::Tip tip_start, tip;    // crack tip at the start and at the end
  double tip_speed = 0;             // m/s, last fitted speed of λx × reference tip x over output.speed_window
  double energy_start = 0, energy_end = 0;  // J, kinetic + potential
  // The energy when the clamped rows stop doing work (t = 0, or the first observation from loading.ramp_time
  // on), and the knife's work by then: undamped, energy_end - energy_conserved equals the knife's work since.
  bool energy_conserved_set = false;
  double energy_conserved = 0, energy_conserved_time = 0, drive_energy_conserved = 0;
  double wall_seconds = 0;
  double loop_seconds = 0;          // wall time of the time loop alone (steps, events, observations)
  long long loop_steps = 0;         // steps of that loop (fewer than `steps` in a run continued from a checkpoint)
  double ns_per_node_step() const {
    return loop_steps > 0 && nodes > 0
               ? 1e9 * loop_seconds / (static_cast<double>(loop_steps) * static_cast<double>(nodes))
               : 0;
  }
  std::size_t nodes = 0;
  int checkpoints = 0;            // written by this process
  double checkpoint_seconds = 0;  // wall time spent writing them
};


// Runs to the stop rule. `writer` may be null (tests, benchmarks). With checkpoints, one is written when due and
// when a stop signal arrives (then Interrupted is thrown).
RubberSummary run_rubber(RubberSystem& system, const RubberSetup& setup, io::RunWriter* writer, Progress& progress,
                         const io::Continuation& continuation = {});

}  // namespace frac::rubber
