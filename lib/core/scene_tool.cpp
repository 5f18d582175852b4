#include "core/scene_tool.hpp"

namespace frac::cli {

SceneToolArgs parse_scene_tool(int argc, const char* const* argv, const ToolSpec& spec) {
  SceneToolArgs a;
  const auto args = split_overrides(argc, argv, a.overrides);
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&a.input)->required(), "mesh file, or - for standard input")(
      "scene", po::value(&a.scene_path)->required(), "scene file (INI)");
  add_common(desc, a.common, kOutput | kQuiet | kSeed | kThreads | kConfig);
  po::positional_options_description positional;
  positional.add("input", 1);
  parse(static_cast<int>(args.size()), args.data(), spec, desc, positional, &a.overrides);
  a.command_line = command_line(argc, argv);
  return a;
}

Scene load_scene(const SceneToolArgs& args) { return Scene::load(args.scene_path, args.overrides); }

ToolRun scene_run(const std::string& tool, const SceneToolArgs& args, const Scene& scene) {
  ToolRun run = start_run(tool, args.command_line);
  run.seed = std::to_string(args.common.seed);
  run.parameters = scene.resolved();
  run.parameters.emplace_back("scene", args.scene_path);
  return run;
}

}  // namespace frac::cli
