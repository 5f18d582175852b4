#pragma once
// The command line of a tool that runs a scene on a mesh (dem-run, rubber-run): MESH|- --scene SCENE.ini, any
// scene key as --section.key VALUE (or in a --config file, which the command line overrides), -o, -q, --seed,
// --threads, the checkpoint options (--checkpoint-every, --checkpoint, --resume); and the provenance record of
// such a run.
#include <string>
#include <utility>
#include <vector>

#include "core/checkpoint_options.hpp"
#include "core/cli.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"

namespace frac::cli {

struct SceneToolArgs {
  std::string input, scene_path;
  CommonOptions common;
  CheckpointOptions checkpoint;
  std::vector<std::pair<std::string, std::string>> overrides;  // scene keys of the command line and --config
  std::string command_line;
  bool profile = false;  // --profile: the time of each phase of a step, at the end
};
SceneToolArgs parse_scene_tool(int argc, const char* const* argv, const ToolSpec& spec);

// The scene file with the overrides applied.
Scene load_scene(const SceneToolArgs& args);

// The provenance record of the run: the command line, the seed, every scene key as resolved and the scene's path.
ToolRun scene_run(const std::string& tool, const SceneToolArgs& args, const Scene& scene);

}  // namespace frac::cli
