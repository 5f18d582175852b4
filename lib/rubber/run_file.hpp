#pragma once
// What rubber-run does between reading its inputs and reporting: the mesh a run needs, the run written to its
// file (docs/SCHEMA.md: header and provenance with the derived parameters, the scene's text, frames,
// observables, break events, the run's summary attributes) atomically, and what it reports.
#include <optional>
#include <string>

#include "core/checkpoint_options.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"
#include "io/hdf5.hpp"
#include "mesh/node_mesh.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"

namespace frac::rubber {

// The node mesh of a mesh file (kind "mesh", nodes); InputError naming `name` for polygon cells.
mesh::NodeMesh read_run_mesh(const io::Group& in, const std::string& name);

// Runs `system` and writes the run file `output` ("-": standard output). `run`: the provenance record so far
// (cli::scene_run); the setup's derived parameters and the input's provenance are added here.
// Checkpoints as `checkpoint` says (io/checkpoint); a run whose checkpoint exists continues from it.
RubberSummary run_to_file(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh,
                          const Scene& scene, ToolRun run, const io::Group& input, const std::string& output,
                          const CheckpointOptions& checkpoint, Progress& progress);

// The one line a run reports: steps, time, stop reason, bonds past u_c, the crack tip and its speed against
// the wave speeds, the driven seed, the energy, the wall time.
std::string summary_line(const RubberSummary& s, const RubberSystem& system, const RubberSetup& setup,
                         const mesh::NodeMesh& mesh);

// Without damping the total energy is conserved up to the integration error (and the small three-body remainder
// of irreversibly broken bonds, and the work of a driven seed's knife, which is booked): a warning when it
// changed by more than 1 %.
std::optional<std::string> energy_warning(const RubberSummary& s, const RubberScene& scene);

}  // namespace frac::rubber
