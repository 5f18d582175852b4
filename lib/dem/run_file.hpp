#pragma once
// What dem-run does between reading its inputs and reporting: the mesh a run needs, and the run written to its
// file (docs/SCHEMA.md: header and provenance with the derived parameters, the scene's text, frames,
// observables, break events, the run's summary attributes), atomically.
#include <string>

#include "core/checkpoint_options.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"
#include "dem/simulation.hpp"
#include "io/hdf5.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

// The cell mesh of a mesh file (kind "mesh", cells); InputError naming `name` for a node mesh.
mesh::CellMesh read_run_mesh(const io::Group& in, const std::string& name);

// Runs `sim` and writes the run file `output` ("-": standard output). `run`: the provenance record so far
// (cli::scene_run); the derived parameters (time step, kick) and the input's provenance are added here.
// Checkpoints as `checkpoint` says (io/checkpoint); a run whose checkpoint exists continues from it.
RunSummary run_to_file(Simulation& sim, const Scene& scene, ToolRun run, const io::Group& input,
                       const std::string& output, const CheckpointOptions& checkpoint, Progress& progress);

// The run's energy balance: its largest error in % of the initial energy or boundary work, or in J when both are 0.
std::string energy_balance_text(const RunSummary& s);

// The one line a run reports: steps, time, stop reason, beams broken, energy balance, wall time.
std::string summary_line(const RunSummary& s, const Simulation& sim);

}  // namespace frac::dem
