#include "rubber/run_file.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "run/run_file.hpp"

namespace frac::rubber {

mesh::NodeMesh read_run_mesh(const io::Group& in, const std::string& name) {
  io::check_header(in, {"mesh"});
  if (io::mesh_kind(in) != io::MeshKind::nodes)
    throw InputError(name + ": holds polygon cells; rubber-run needs a node mesh (mesh-gen triangular)");
  return io::read_node_mesh(in);
}

RubberSummary run_to_file(RubberSystem& system, const RubberSetup& setup, const mesh::NodeMesh& mesh,
                          const Scene& scene, ToolRun run, const io::Group& input, const std::string& output,
                          const CheckpointOptions& checkpoint, Progress& progress) {
  for (auto& d : setup.derived()) run.parameters.push_back(std::move(d));
  RubberRun engine(system, setup, mesh);
  const run::FileOutcome f =
      run::run_to_file(engine, "rubber-run", scene.source_text(), std::move(run), input, output, checkpoint, progress);
  RubberSummary s = engine.summary(f.run);
  s.checkpoints = f.checkpoints;
  s.checkpoint_seconds = f.checkpoint_seconds;
  return s;
}

std::string summary_line(const RubberSummary& s, const RubberSystem& system, const RubberSetup& setup,
                         const mesh::NodeMesh& mesh) {
  std::ostringstream line;
  line.precision(4);
  line << s.steps << " steps of " << s.dt << " s to t = " << s.time << " s (" << s.stop_reason << "), " << s.events
       << " bonds past u_c";
  if (s.tip.found)
    line << ", crack tip advanced " << (s.tip.reference_x - s.tip_start.reference_x) / mesh.spacing
         << " spacings (last speed " << s.tip_speed << " m/s; lattice c_T " << setup.lattice_x.transverse << ", c_L "
         << setup.lattice_x.longitudinal << " m/s along x)";
  if (system.drive) line << ", the driven seed cut " << s.driven << " bonds (knife's work " << s.drive_energy << " J)";
  line << ", energy " << s.energy_start << " -> " << s.energy_end << " J, " << s.wall_seconds << " s wall ("
       << s.ns_per_node_step() << " ns per node-step on " << system.model->threads() << " thread"
       << (system.model->threads() > 1 ? "s" : "") << ")";
  if (s.checkpoints > 0) line << ", " << s.checkpoints << " checkpoints (" << s.checkpoint_seconds << " s)";
  return line.str();
}

std::optional<std::string> energy_warning(const RubberSummary& s, const RubberScene& scene) {
  if (scene.damping || !s.energy_conserved_set) return std::nullopt;
  const double knife = s.drive_energy - s.drive_energy_conserved;
  const double change =
      std::abs(s.energy_end - s.energy_conserved - knife) / std::max(std::abs(s.energy_conserved), 1e-300);
  if (!(change > 0.01)) return std::nullopt;
  std::ostringstream m;
  m << "the total energy changed by " << 100 * change << "% without damping";
  if (s.energy_conserved_time > 0) m << " since the clamped rows stopped (t = " << s.energy_conserved_time << " s)";
  m << ": the time step is too large for this scene (lower integrator.safety)";
  if (s.irreversible > 0)
    m << ", or irreversible breaking removed bonds (" << s.irreversible
      << ") before their cut-off had faded (raise breaking.extra_widths)";
  return m.str();
}

}  // namespace frac::rubber
