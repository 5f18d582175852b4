// dem-run: the polygon DEM of Kun, D'Addetta, Herrmann and Ramm (1999) on a Voronoi mesh, under a scene.
#include <iostream>
#include <sstream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"
#include "dem/simulation.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"

using namespace frac;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  return cli::run_tool("dem-run", [&] {
    const cli::ToolSpec spec{
        "dem-run", "--scene SCENE.ini MESH|- [--section.key VALUE ...] -o RUN.h5",
        "Runs the polygon DEM on a mesh from mesh-gen voronoi under a scene (data/scenes/*.ini): beams, overlap "
        "contacts, damping and friction as the scene's [physics] names them; Gear's 5th-order predictor-corrector "
        "or velocity Verlet. Any scene key can be overridden, e.g. --material.t_eps 0.02 (or material.t_eps = 0.02 in "
        "a --config file, which the command line overrides in turn). Writes the mesh, the "
        "resolved scene, trajectory frames, observables and beam-break events (docs/SCHEMA.md).",
        "  mesh-gen voronoi --shape disc --diameter 0.4 --cells 1100 --seed 7 -o disc.h5\n"
        "  dem-run --scene data/scenes/explosion.ini disc.h5 -o explosion.h5\n"
        "  dem-run --scene data/scenes/explosion.ini disc.h5 --material.t_eps 0.02 --integrator.kind verlet -o e.h5\n"
        "  dem-run --scene data/scenes/explosion.ini disc.h5 --threads 2 -o explosion.h5   # same bits, faster\n"
        "  printf 'scene = data/scenes/explosion.ini\\n[material]\\nt_eps = 0.02\\n' > e.cfg && "
        "dem-run --config e.cfg disc.h5 -o e.h5"};
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
    set_threads(common.threads);

    Scene scene = Scene::load(scene_path, overrides);
    dem::require_run_keys(scene);
    const dem::DemScene resolved = dem::read_dem_scene(scene);
    scene.check_all_used();

    const io::Group in = io::open_input(input);
    io::check_header(in, {"mesh"});
    if (io::mesh_kind(in) != io::MeshKind::cells)
      throw InputError(input + ": holds a node mesh; dem-run needs cells (mesh-gen voronoi)");
    const mesh::CellMesh mesh = io::read_cell_mesh(in);
    dem::Simulation sim(mesh, resolved);

    ToolRun run = start_run("dem-run", cli::command_line(argc, argv));
    run.seed = std::to_string(common.seed);
    run.parameters = scene.resolved();
    run.parameters.emplace_back("scene", scene_path);
    auto exact = [](double x) {  // std::to_string keeps 6 decimals: 1.3e-6 s would read 0.000001
      std::ostringstream s;
      s.precision(17);
      s << x;
      return s.str();
    };
    run.parameters.emplace_back("derived.dt", exact(sim.time_step.dt));
    run.parameters.emplace_back("derived.dt_bound", exact(sim.time_step.bound));
    run.parameters.emplace_back("derived.omega_max", exact(sim.time_step.omega_max));
    const dem::KickReport kick = dem::kick_report(sim);
    if (kick.cells > 0) {
      run.parameters.emplace_back("derived.kick_cells", std::to_string(kick.cells));
      run.parameters.emplace_back("derived.kick_kinetic_energy", std::to_string(kick.kinetic_energy));
      run.parameters.emplace_back("derived.kick_mean_speed", std::to_string(kick.mean_speed));
      std::ostringstream m;
      m << kick.momentum_over_scale;
      run.parameters.emplace_back("derived.kick_momentum_over_scale", m.str());
    }
    io::add_input(run, in);
    io::OutputFile out(common.output);
    io::write_header(out.root(), "run", run, out.uuid());
    out.root().group("parameters/dem-run").write_strings("scene_text", {scene.source_text()});
    io::RunWriter writer(out.root(), mesh, sim.model.bodies().mass, sim.model.bodies().inertia);

    Progress progress("dem-run", common.quiet);
    const dem::RunSummary s = sim.run(&writer, progress);
    out.root().set_attr("steps", static_cast<std::int64_t>(s.steps));
    out.root().set_attr("end_time", s.time);
    out.root().set_attr("stop_reason", s.stop_reason);
    out.root().set_attr("wall_seconds", s.wall_seconds, "provenance");  // differs run to run: not data
    out.root().set_attr("start_evaluations", static_cast<std::int64_t>(s.start_evaluations));
    out.commit();
    std::ostringstream line;
    line.precision(4);
    line << s.steps << " steps of " << s.dt << " s to t = " << s.time << " s (" << s.stop_reason << "), "
         << s.broken << " of " << sim.model.beams().size() << " beams broken, energy balance within "
         << s.energy_error / std::max(s.energy_scale, 1e-300) * 100 << "% , " << s.wall_seconds << " s wall";
    progress.finish(line.str());
    return kExitOk;
  });
}
