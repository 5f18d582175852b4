// rubber-run: Marder's two- and three-body lattice model of Mooney-Rivlin rubber on a triangular mesh,
// under a scene (stretch with a seeded crack, or a wave pulse).
#include <iostream>
#include <sstream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"
#include "rubber/run.hpp"
#include "rubber/setup.hpp"

using namespace frac;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  return cli::run_tool("rubber-run", [&] {
    const cli::ToolSpec spec{
        "rubber-run", "--scene SCENE.ini MESH|- [--section.key VALUE ...] -o RUN.h5",
        "Runs Marder's rubber lattice (pair and three-body forces whose continuum limit is Mooney-Rivlin rubber, "
        "bonds failing through a cut-off) on a triangular mesh from mesh-gen triangular, under a scene "
        "(data/scenes/stretch.ini: a pre-stretched strip with a seeded crack; wave.ini: a pulse in a stretched "
        "sheet). Velocity Verlet by default. Any scene key can be overridden, e.g. --law.cutoff_length 3.6e-3 (or "
        "law.cutoff_length = 3.6e-3 in a --config file, which the command line overrides in turn). "
        "Warns when the cut-off stiffens the far field or a bond family is not Mooney-Rivlin. Writes the mesh, the "
        "resolved scene, frames, observables (energies, crack tip and speed) and bond-break events "
        "(docs/rubber-run.md, docs/SCHEMA.md).",
        "  mesh-gen triangular --nodes 400x80 --spacing 1e-3 --notch 0.02 -o strip.h5\n"
        "  rubber-run --scene data/scenes/stretch.ini strip.h5 -o crack.h5\n"
        "  mesh-gen triangular --nodes 200x40 --spacing 1e-3 | rubber-run --scene data/scenes/stretch.ini - "
        "--loading.stretch_y 3.5 --physics.damping on -o crack.h5"};
    std::vector<std::pair<std::string, std::string>> overrides;
    const auto args = cli::split_overrides(argc, argv, overrides);
    cli::CommonOptions common;
    std::string input, scene_path;
    po::options_description desc("Options");
    desc.add_options()("input", po::value(&input)->required(), "mesh file, or - for standard input")(
        "scene", po::value(&scene_path)->required(), "scene file (INI)");
    cli::add_common(desc, common, cli::kOutput | cli::kQuiet | cli::kSeed | cli::kThreads | cli::kConfig);
    po::positional_options_description positional;
    positional.add("input", 1);
    const auto vm = cli::parse(static_cast<int>(args.size()), args.data(), spec, desc, positional, &overrides);
    set_threads(1);  // The shared thread team (the integrator's loops) stays on one thread: the model's own pool
                     // runs common.threads workers, and idle workers spinning beside it would slow them

    Scene scene = Scene::load(scene_path, overrides);

    const io::Group in = io::open_input(input);
    io::check_header(in, {"mesh"});
    if (io::mesh_kind(in) != io::MeshKind::nodes)
      throw InputError(input + ": holds polygon cells; rubber-run needs a node mesh (mesh-gen triangular)");
    const mesh::NodeMesh mesh = io::read_node_mesh(in);

    rubber::require_run_keys(scene);
    const rubber::RubberScene resolved = rubber::read_rubber_scene(scene, mesh);
    scene.check_all_used();
    const rubber::RubberSetup setup = rubber::prepare_rubber(resolved, mesh);
    if (!common.quiet)
      for (const auto& w : setup.warnings) std::cerr << "rubber-run: warning: " << w << "\n";
    rubber::RubberSystem system = rubber::build_rubber(mesh, setup, common.seed, common.threads);

    ToolRun run = start_run("rubber-run", cli::command_line(argc, argv));
    run.seed = std::to_string(common.seed);
    run.parameters = scene.resolved();
    run.parameters.emplace_back("scene", scene_path);
    for (auto& d : setup.derived()) run.parameters.push_back(std::move(d));
    io::add_input(run, in);
    io::OutputFile out(common.output);
    io::write_header(out.root(), "run", run, out.uuid());
    out.root().group("parameters/rubber-run").write_strings("scene_text", {scene.source_text()});
    const std::vector<double> mass(mesh.nodes(), setup.node_mass);
    io::RunWriter writer(out.root(), mesh, mass);

    Progress progress("rubber-run", common.quiet);
    const rubber::RubberSummary s = rubber::run_rubber(system, setup, &writer, progress);
    out.root().set_attr("steps", static_cast<std::int64_t>(s.steps));
    out.root().set_attr("end_time", s.time);
    out.root().set_attr("stop_reason", s.stop_reason);
    out.commit();

    std::ostringstream line;
    line.precision(4);
    line << s.steps << " steps of " << s.dt << " s to t = " << s.time << " s (" << s.stop_reason << "), "
         << s.events << " bonds past u_c";
    if (s.tip.found)
      line << ", crack tip advanced " << (s.tip.reference_x - s.tip_start.reference_x) / mesh.spacing
           << " spacings (last speed " << s.tip_speed << " m/s; lattice c_T " << setup.lattice_x.transverse
           << ", c_L " << setup.lattice_x.longitudinal << " m/s along x)";
    if (system.drive)
      line << ", the driven seed cut " << s.driven << " bonds (knife's work " << s.drive_energy << " J)";
    line << ", energy " << s.energy_start << " -> " << s.energy_end << " J, " << s.wall_seconds << " s wall ("
         << s.ns_per_node_step() << " ns per node-step on " << system.model->threads() << " thread"
         << (system.model->threads() > 1 ? "s" : "") << ")";
    progress.finish(line.str());
    // Without damping the total energy is conserved up to the integration error (and the small
    // three-body remainder of irreversibly broken bonds, and the work of a driven seed's knife, which is
    // booked): say so when it is not.
    const double change =
        std::abs(s.energy_end - s.energy_start - s.drive_energy) / std::max(std::abs(s.energy_start), 1e-300);
    if (!resolved.damping && change > 0.01 && !common.quiet)
      std::cerr << "rubber-run: warning: the total energy changed by " << 100 * change
                << "% without damping: the time step is too large for this scene (lower integrator.safety)\n";
    return kExitOk;
  });
}
