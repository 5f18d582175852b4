#include "core/scene_tool.hpp"

#include "core/file_roles.hpp"

namespace frac::cli {

SceneToolArgs parse_scene_tool(int argc, const char* const* argv, const ToolSpec& spec) {
  SceneToolArgs a;
  const auto args = split_overrides(argc, argv, a.overrides);
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&a.input)->required(), "mesh file, or - for standard input")(
      "scene", po::value(&a.scene_path)->required(), "scene file (INI)");
  add_common(desc, a.common, kOutput | kQuiet | kSeed | kThreads | kConfig);
  std::string every = "15min";
  desc.add_options()("checkpoint-every", po::value(&every)->default_value(every),
                     "write a checkpoint every N steps, or every wall-clock time (600s, 15min, 2h); 0: only when "
                     "stopped by SIGTERM or SIGINT (a run always writes one then)")(
      "checkpoint", po::value(&a.checkpoint.path)->value_name("FILE"),
      "the checkpoint file (default: the output's name + .ckpt; none for -o -)")(
      "resume", po::value(&a.checkpoint.resume)->value_name("FILE"),
      "continue the run of this checkpoint (the same command line finds the default checkpoint by itself)")(
      "profile", po::bool_switch(&a.profile),
      "at the end, print the time of each phase of a step (core/phases) and the share of the serial ones");
  po::positional_options_description positional;
  positional.add("input", 1);
  parse(static_cast<int>(args.size()), args.data(), spec, desc, positional, &a.overrides);
  a.command_line = command_line(argc, argv);
  parse_checkpoint_every(every, "--checkpoint-every", a.checkpoint);
  const std::string checkpoint = checkpoint_path(a.checkpoint, a.common.output);
  // (resuming from the file the run checkpoints to is the usual case, not a clash)
  const bool resume_in_place = !a.checkpoint.resume.empty() && same_file(a.checkpoint.resume, checkpoint);
  check_file_roles({{"MESH", a.input},
                    {"--scene", a.scene_path},
                    {"--config", a.common.config},
                    {"--resume", resume_in_place ? "" : a.checkpoint.resume}},
                   {{"-o", a.common.output}, {"--checkpoint", checkpoint}});
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
