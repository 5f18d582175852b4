// dem-run: the polygon DEM of Kun, D'Addetta, Herrmann and Ramm (1999) on a Voronoi mesh, under a scene.
#include <iostream>

#include "comm/world.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/progress.hpp"
#include "core/scene_tool.hpp"
#include "dem/run_file.hpp"
#include "dem/simulation.hpp"
#include "io/hdf5.hpp"

using namespace frac;

int main(int argc, char** argv) {
  return cli::run_tool("dem-run", [&] {
    comm::require_one_rank(comm::World::start(argc, argv));
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
    const cli::SceneToolArgs args = cli::parse_scene_tool(argc, argv, spec);
    set_threads(args.common.threads);

    Scene scene = cli::load_scene(args);
    dem::require_run_keys(scene);
    const dem::DemScene resolved = dem::read_dem_scene(scene);
    scene.check_all_used();

    const io::Group in = io::open_input(args.input);
    const mesh::CellMesh mesh = dem::read_run_mesh(in, args.input);
    dem::Simulation sim(mesh, resolved);

    Progress progress("dem-run", args.common.quiet);
    const dem::RunSummary s = dem::run_to_file(sim, scene, cli::scene_run("dem-run", args, scene), in,
                                               args.common.output, args.checkpoint, progress);
    progress.finish(dem::summary_line(s, sim));
    if (args.profile)
      write_phase_table(std::cerr, "dem-run: phases of " + std::to_string(s.steps) + " steps", s.phases);
    return kExitOk;
  });
}
