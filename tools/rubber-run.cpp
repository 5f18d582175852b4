// rubber-run: Marder's two- and three-body lattice model of Mooney-Rivlin rubber on a triangular mesh,
// under a scene (stretch with a seeded crack, or a wave pulse).
#include <iostream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/progress.hpp"
#include "core/scene_tool.hpp"
#include "io/hdf5.hpp"
#include "rubber/run.hpp"
#include "rubber/run_file.hpp"
#include "rubber/setup.hpp"

using namespace frac;

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
    const cli::SceneToolArgs args = cli::parse_scene_tool(argc, argv, spec);
    set_threads(args.common.threads);

    Scene scene = cli::load_scene(args);
    const io::Group in = io::open_input(args.input);
    const mesh::NodeMesh mesh = rubber::read_run_mesh(in, args.input);
    rubber::require_run_keys(scene);
    const rubber::RubberScene resolved = rubber::read_rubber_scene(scene, mesh);
    scene.check_all_used();
    const rubber::RubberSetup setup = rubber::prepare_rubber(resolved, mesh);
    if (!args.common.quiet)
      for (const auto& w : setup.warnings) std::cerr << "rubber-run: warning: " << w << "\n";
    rubber::RubberSystem system = rubber::build_rubber(mesh, setup, args.common.seed, args.common.threads);

    Progress progress("rubber-run", args.common.quiet);
    const rubber::RubberSummary s =
        rubber::run_to_file(system, setup, mesh, scene, cli::scene_run("rubber-run", args, scene), in,
                            args.common.output, args.checkpoint, progress);
    progress.finish(rubber::summary_line(s, system, setup, mesh));
    if (args.profile)
      write_phase_table(std::cerr, "rubber-run: phases of " + std::to_string(s.steps) + " steps", s.phases);
    if (const auto warning = rubber::energy_warning(s, resolved); warning && !args.common.quiet)
      std::cerr << "rubber-run: warning: " << *warning << "\n";
    return kExitOk;
  });
}
