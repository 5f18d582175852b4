#pragma once
// A run written to its file (docs/SCHEMA.md, "Run files"), atomically: header and provenance (the caller's
// record with its derived parameters, and the input's), the scene's text, the mesh and per-body constants, the
// engine's frames, observables and break events, and the run's summary attributes; checkpoints as `checkpoint`
// says (a run whose checkpoint exists continues from it), a runtime failure naming the last good checkpoint.
#include <string>

#include "core/checkpoint_options.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "io/hdf5.hpp"
#include "run/driver.hpp"
#include "run/engine.hpp"

namespace frac::run {

struct FileOutcome {
  Outcome run;
  int checkpoints = 0;            // written by this process
  double checkpoint_seconds = 0;  // wall time spent writing them
};

// Runs `engine` and writes the run file `output` ("-": standard output) of `tool` (its scene's text under
// /parameters/<tool>/scene_text). `run`: the provenance record (cli::scene_run, with the derived parameters);
// the input's provenance is added here.
FileOutcome run_to_file(Engine& engine, const std::string& tool, const std::string& scene_text, ToolRun run,
                        const io::Group& input, const std::string& output, const CheckpointOptions& checkpoint,
                        Progress& progress);

}  // namespace frac::run
