#include "run/run_file.hpp"

#include "io/checkpoint.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"

namespace frac::run {
namespace {

io::RunWriter make_writer(io::Group& root, const RunBodies& b) {
  if (b.cells) return io::RunWriter(root, *b.cells, b.mass, b.inertia);
  return io::RunWriter(root, *b.nodes, b.mass);
}

}  // namespace

FileOutcome run_to_file(Engine& engine, const std::string& tool, const std::string& scene_text, ToolRun run,
                        const io::Group& input, const std::string& output, const CheckpointOptions& checkpoint,
                        Progress& progress) {
  io::add_input(run, input);
  io::RunCheckpoints checkpoints(checkpoint, output, run, [&](const std::string& m) { progress.note(m); });
  io::OutputFile out(output);
  io::write_header(out.root(), "run", run, out.uuid());
  out.root().group("parameters/" + tool).write_strings("scene_text", {scene_text});
  io::RunWriter writer = make_writer(out.root(), engine.bodies());
  declare_frames(engine, writer);
  const io::Continuation continuation = checkpoints.start(writer);
  FileOutcome f;
  f.run = checkpoints.guard([&] {
    const Outcome r = drive(engine, &writer, progress, continuation);
    out.root().set_attr("steps", static_cast<std::int64_t>(r.steps));
    out.root().set_attr("end_time", r.time);
    out.root().set_attr("stop_reason", r.stop_reason);
    out.root().set_attr("wall_seconds", r.wall_seconds, "provenance");  // differs run to run: not data
    for (const auto& [name, value] : engine.run_attributes()) out.root().set_attr(name, value);
    out.commit();
    return r;
  });
  f.checkpoints = checkpoints.written();
  f.checkpoint_seconds = checkpoints.seconds();
  checkpoints.finish();
  return f;
}

}  // namespace frac::run
