#pragma once
// Checkpoints of a run (docs/SCHEMA.md, "Checkpoints"): a file of kind "checkpoint" holding the run's identity
// (the tool, its version, the seed, every resolved parameter and the inputs' uuids), the output written so far
// (/run: the trajectory series, the observables and the break events, as in the run file) and the state a
// continuation needs (/state, named by the objects' visit_state, with a checksum). It is written atomically
// and durably (synced before the rename onto the last one) and removed once the run's output is in place.
// A continuation rebuilds the run from its inputs as a fresh run would, replays /run into its new output and
// loads /state over what it built: the output is the uninterrupted run's, bit for bit.
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/checkpoint_options.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/provenance.hpp"
#include "core/state_archive.hpp"
#include "io/hdf5.hpp"
#include "io/run_io.hpp"

namespace frac::io {

// The state archive of a checkpoint's /state group. Saving writes each array as it comes and, at finish(), the
// list of entries and their checksum.
class StateWriter final : public StateArchive {
 public:
  explicit StateWriter(Group group) : group_(std::move(group)) {}
  bool loading() const override { return false; }
  void finish();

 private:
  void save(const std::string& name, Type type, const void* data, std::size_t count) override;
  std::size_t stored(const std::string& name, Type type) override;
  void load(const std::string& name, Type type, void* data, std::size_t count) override;
  std::string where(const std::string& name) const override;
  Group group_;
  std::vector<std::string> names_;
  std::uint64_t checksum_ = 0xcbf29ce484222325ull;  // FNV-1a's offset basis: nothing saved yet
};

// Loading: every entry read at construction and checked against the checksum (InputError naming the group for
// a damaged state), then handed out by name.
class StateReader final : public StateArchive {
 public:
  explicit StateReader(const Group& group);
  bool loading() const override { return true; }

 private:
  void save(const std::string& name, Type type, const void* data, std::size_t count) override;
  std::size_t stored(const std::string& name, Type type) override;
  void load(const std::string& name, Type type, void* data, std::size_t count) override;
  std::string where(const std::string& name) const override;
  struct Entry {
    Type type;
    std::vector<unsigned char> bytes;
  };
  std::string where_;
  std::map<std::string, Entry> entries_;
};

// A run that stopped on a runtime failure (a full disk, a file size limit, an unwritable checkpoint): the
// message says so and names the last good checkpoint, which is intact.
struct RunStopped : RuntimeError {
  using RuntimeError::RuntimeError;
};

// What must match for a checkpoint to continue a run: tool, version, seed, parameters but the scene file's path,
// input uuids; one "key=value" a line.
std::string run_key(const ToolRun& run);

// The checkpoints of one run: when one is due, and writing it.
class Checkpoints {
 public:
  // None when `path` is empty (standard output without --checkpoint). `last_path` and `last_step`: the
  // checkpoint the run continued from ("" : none).
  Checkpoints(const CheckpointOptions& options, std::string path, const ToolRun& run, RunWriter* writer,
              std::string last_path = "", std::int64_t last_step = -1);
  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }
  // Whether a periodic checkpoint is due after `step` (steps, or wall-clock time since the last).
  bool due(std::int64_t step) const;
  // Writes one: the output so far (through the writer) and the state `visit` names. On a failure, RunStopped
  // naming the cause, the step and the last good checkpoint (the one before stays until the new one is whole).
  void write(std::int64_t step, double time, const std::function<void(StateArchive&)>& visit);
  // "the run stopped [after step N]; its last checkpoint, FILE (step M), is intact: ..." (or that there is none).
  std::string stopped_note(std::int64_t step = -1) const;
  // After the output is in place: the checkpoint is removed.
  void remove();
  // A stop signal noted (core/signals): the checkpoint written (when enabled) and Interrupted thrown, naming the
  // signal, the step and how to continue.
  void stop_if_signalled(std::int64_t step, double time, const std::function<void(StateArchive&)>& visit);
  int written() const { return written_; }
  double seconds() const { return seconds_; }  // wall time spent writing them

 private:
  CheckpointOptions options_;
  std::string path_;
  ToolRun run_;
  std::string key_;
  RunWriter* writer_;
  std::chrono::steady_clock::time_point last_time_;
  std::string last_path_;        // the last good checkpoint ("" : none)
  std::int64_t last_step_ = -1;  // its step
  int written_ = 0;
  double seconds_ = 0;
};

// A checkpoint to continue from.
class Resume {
 public:
  // --resume FILE (it must exist and hold this run's checkpoint: InputError otherwise), or else the default
  // checkpoint `path` if it exists: this run's, it is taken; another run's, `warn` says so and the run starts
  // afresh. None: start afresh. Taken, run.segments gets the checkpoint's segments and this one.
  static std::optional<Resume> find(const CheckpointOptions& options, const std::string& path, ToolRun& run,
                                    const std::function<void(const std::string&)>& warn);
  const Group& output() const { return *run_; }  // the output so far, for RunWriter::replay
  StateArchive& state() { return *state_; }
  std::int64_t step() const { return step_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::optional<Group> root_, run_;
  std::unique_ptr<StateReader> state_;
  std::int64_t step_ = 0;
};

// What a run loop needs of its checkpoints: where they go, and the state to continue from.
struct Continuation {
  Checkpoints* checkpoints = nullptr;  // null: none (tests, benchmarks), and stop signals act at once
  StateArchive* resume = nullptr;      // null: a fresh run; else loaded over the fresh start (the writer already
                                       // holds the output so far)
};

// The checkpoints of a run writing `output`, as a tool runs them: a checkpoint to continue from is looked for
// first (Resume::find; its segments go into `run` before the output's header is written); once the output's
// writer exists, start() replays the output so far into it; after the output is in place, finish() removes
// the checkpoint. Notes (continuing, or a checkpoint of another run) go to `note`. The checkpoint is a file
// (UsageError for a device, a FIFO or standard output; none by default for an output that is not a file), in a
// folder the run can write to, checked before the run starts.
class RunCheckpoints {
 public:
  RunCheckpoints(const CheckpointOptions& options, const std::string& output, ToolRun& run,
                 const std::function<void(const std::string&)>& note);
  Continuation start(RunWriter& writer);
  // Runs `body` (the run and the writing of its output) after start(): a runtime failure in it (a full disk, a
  // file size limit, no memory) stops the run with RunStopped, naming the last good checkpoint.
  template <class Body>
  auto guard(Body&& body) -> decltype(body()) {
    try {
      return body();
    } catch (const RunStopped&) {
      throw;
    } catch (const RuntimeError& e) {
      throw RunStopped(std::string(e.what()) + "; " + checkpoints_->stopped_note());
    } catch (const std::bad_alloc&) {
      throw RunStopped(std::string(out_of_memory("the run").what()) + "; " + checkpoints_->stopped_note());
    }
  }
  void finish() { checkpoints_->remove(); }
  int written() const { return checkpoints_ ? checkpoints_->written() : 0; }
  double seconds() const { return checkpoints_ ? checkpoints_->seconds() : 0; }

 private:
  CheckpointOptions options_;
  std::string path_;
  const ToolRun& run_;
  std::function<void(const std::string&)> note_;
  std::optional<Resume> resume_;
  std::optional<Checkpoints> checkpoints_;
};

}  // namespace frac::io
