#pragma once
// When a run writes checkpoints and where, and what it resumes from (dem-run, rubber-run: --checkpoint-every,
// --checkpoint, --resume; io/checkpoint writes and reads them).
#include <cstdint>
#include <string>

namespace frac {

struct CheckpointOptions {
  std::int64_t every_steps = 0;  // a checkpoint every this many steps (0: not by steps)
  double every_seconds = 900;    // or of wall-clock time, s (0: not by time)
  std::string path;              // the checkpoint file; "" : the output's name + ".ckpt" (none for standard output)
  std::string resume;            // --resume FILE: continue from it ("" : from `path` if it holds this run's checkpoint)
  bool periodic() const { return every_steps > 0 || every_seconds > 0; }
};

// --checkpoint-every: "N" steps, a wall-clock time "Ns", "Nmin" or "Nh", or "0" (none but on a stop signal).
// UsageError naming `option` otherwise.
void parse_checkpoint_every(const std::string& text, const std::string& option, CheckpointOptions& out);

// The checkpoint file of a run writing `output`: options.path, or output + ".ckpt"; "" for standard output.
std::string checkpoint_path(const CheckpointOptions& options, const std::string& output);

}  // namespace frac
