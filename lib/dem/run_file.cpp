#include "dem/run_file.hpp"

#include <sstream>

#include "core/error.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "run/run_file.hpp"

namespace frac::dem {
namespace {

std::string exact(double x) {  // (std::to_string keeps 6 decimals: 1.3e-6 s would read 0.000001)
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// The values the run derived from the scene and the mesh: the time step and its bound, and the initial kick.
void add_derived(ToolRun& run, const Simulation& sim) {
  run.parameters.emplace_back("derived.dt", exact(sim.time_step.dt));
  run.parameters.emplace_back("derived.dt_bound", exact(sim.time_step.bound));
  run.parameters.emplace_back("derived.omega_max", exact(sim.time_step.omega_max));
  const KickReport kick = kick_report(sim);
  if (kick.cells == 0) return;
  run.parameters.emplace_back("derived.kick_cells", std::to_string(kick.cells));
  run.parameters.emplace_back("derived.kick_kinetic_energy", std::to_string(kick.kinetic_energy));
  run.parameters.emplace_back("derived.kick_mean_speed", std::to_string(kick.mean_speed));
  std::ostringstream m;
  m << kick.momentum_over_scale;
  run.parameters.emplace_back("derived.kick_momentum_over_scale", m.str());
}

}  // namespace

mesh::CellMesh read_run_mesh(const io::Group& in, const std::string& name) {
  io::check_header(in, {"mesh"});
  if (io::mesh_kind(in) != io::MeshKind::cells)
    throw InputError(name + ": holds a node mesh; dem-run needs cells (mesh-gen voronoi)");
  return io::read_cell_mesh(in);
}

RunSummary run_to_file(Simulation& sim, const Scene& scene, ToolRun run, const io::Group& input,
                       const std::string& output, const CheckpointOptions& checkpoint, Progress& progress) {
  add_derived(run, sim);
  DemRun engine = sim.engine();
  const run::FileOutcome f =
      run::run_to_file(engine, "dem-run", scene.source_text(), std::move(run), input, output, checkpoint, progress);
  RunSummary s = engine.summary(f.run);
  s.checkpoints = f.checkpoints;
  s.checkpoint_seconds = f.checkpoint_seconds;
  return s;
}

std::string energy_balance_text(const RunSummary& s) {
  std::ostringstream text;
  text.precision(4);
  text << "energy balance within ";
  // (A run that starts at rest with no boundary work has no energy to compare with: the error in joules.)
  if (s.energy_scale > 0)
    text << s.energy_error / s.energy_scale * 100 << " %";
  else
    text << s.energy_error << " J (no initial energy or boundary work)";
  return text.str();
}

std::string summary_line(const RunSummary& s, const Simulation& sim) {
  std::ostringstream line;
  line.precision(4);
  line << s.steps << " steps of " << s.dt << " s to t = " << s.time << " s (" << s.stop_reason << "), " << s.broken
       << " of " << sim.model.beams().size() << " beams broken, " << energy_balance_text(s) << ", " << s.wall_seconds
       << " s wall";
  if (s.checkpoints > 0) line << " (" << s.checkpoints << " checkpoints, " << s.checkpoint_seconds << " s)";
  return line.str();
}

}  // namespace frac::dem
