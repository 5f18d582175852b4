#include "dem/run_file.hpp"

#include <sstream>

#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"

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
  io::add_input(run, input);
  io::RunCheckpoints checkpoints(checkpoint, output, run, [&](const std::string& m) { progress.note(m); });
  io::OutputFile out(output);
  io::write_header(out.root(), "run", run, out.uuid());
  out.root().group("parameters/dem-run").write_strings("scene_text", {scene.source_text()});
  io::RunWriter writer(out.root(), *sim.cell_mesh, sim.model.bodies().mass, sim.model.bodies().inertia);
  const io::Continuation continuation = checkpoints.start(writer);
  RunSummary s = checkpoints.guard([&] {
    RunSummary r = sim.run(&writer, progress, continuation);
    out.root().set_attr("steps", static_cast<std::int64_t>(r.steps));
    out.root().set_attr("end_time", r.time);
    out.root().set_attr("stop_reason", r.stop_reason);
    out.root().set_attr("wall_seconds", r.wall_seconds, "provenance");  // differs run to run: not data
    out.root().set_attr("start_evaluations", static_cast<std::int64_t>(r.start_evaluations));
    out.commit();
    return r;
  });
  s.checkpoints = checkpoints.written();
  s.checkpoint_seconds = checkpoints.seconds();
  checkpoints.finish();
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
       << " of " << sim.model.beams().size() << " beams broken, " << energy_balance_text(s) << ", "
       << s.wall_seconds << " s wall";
  if (s.checkpoints > 0) line << " (" << s.checkpoints << " checkpoints, " << s.checkpoint_seconds << " s)";
  return line.str();
}

}  // namespace frac::dem
