#pragma once
// The run loop, written once for both engines (run/engine): the engine's step phases on its team, the beams or
// bonds that broke recorded, observations and frames as its schedule says (the final state always observed and
// framed), checkpoints when due and when a stop signal arrives (core/signals), the progress line. A checkpoint
// holds the engine's state registry and the loop's own counters (under "run/").
#include <cstdint>
#include <string>
#include <vector>

#include "core/phases.hpp"
#include "core/progress.hpp"
#include "run/engine.hpp"

namespace frac::io {
class RunWriter;
struct Continuation;
}  // namespace frac::io

namespace frac::run {

struct Outcome {
  std::int64_t steps = 0;  // the step the run ended at
  double time = 0;         // s
  std::string stop_reason;
  double wall_seconds = 0;        // since the progress clock started
  std::int64_t loop_steps = 0;    // steps of this process's loop (fewer than `steps` in a continued run)
  double loop_seconds = 0;        // wall time of that loop
  std::vector<PhaseTime> phases;  // the time of each phase of the steps
};

// Runs `engine` (started here, or continued from `continuation`) to its stop rule, writing through `writer` (null:
// nothing written). With checkpoints, one is written when due and when a stop signal arrives (then Interrupted
// is thrown).
Outcome drive(Engine& engine, io::RunWriter* writer, Progress& progress, const io::Continuation& continuation);
// The same without output or checkpoints (tests, benchmarks).
Outcome drive(Engine& engine, Progress& progress);

// Declares the engine's frame datasets to `writer` as its trajectory (before a checkpoint's output is replayed
// into it; drive does it when nothing was).
void declare_frames(const Engine& engine, io::RunWriter& writer);

}  // namespace frac::run
