#include "io/checkpoint.hpp"

#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "core/signals.hpp"
#include "core/version.hpp"
#include "io/atomic_file.hpp"
#include "io/checksum.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/output_target.hpp"

namespace frac::io {
namespace {

constexpr const char* kTypeName[] = {"float64", "int64", "uint8"};
constexpr std::size_t kTypeBytes[] = {8, 8, 1};
constexpr const char* kEntries = "_entries";  // "type name" of every entry, in the order saved

// The checksum of one entry: its name, type, count and bytes.
struct EntryChecksum : Checksum {
  void add_entry(const std::string& name, int type, const void* data, std::size_t count, std::size_t element) {
    add(name.data(), name.size());
    const std::uint64_t head[2] = {static_cast<std::uint64_t>(type), count};
    add(head, sizeof head);
    add(data, count * element);
  }
};

}  // namespace

// ---------------------------------------------------------------- StateWriter

void StateWriter::save(const std::string& name, Type type, const void* data, std::size_t count) {
  EntryChecksum c;
  c.h = checksum_;
  c.add_entry(name, static_cast<int>(type), data, count, kTypeBytes[static_cast<int>(type)]);
  checksum_ = c.h;
  names_.push_back(std::string(kTypeName[static_cast<int>(type)]) + " " + name);
  const std::vector<hsize_t> dims{count};
  switch (type) {
    case Type::float64:
      group_.write(name, std::span<const double>(static_cast<const double*>(data), count), dims);
      break;
    case Type::int64:
      group_.write(name, std::span<const std::int64_t>(static_cast<const std::int64_t*>(data), count), dims);
      break;
    case Type::uint8:
      group_.write(name, std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(data), count), dims);
      break;
  }
}

void StateWriter::finish() {
  group_.write_strings(kEntries, names_);
  group_.set_attr("checksum", static_cast<std::int64_t>(checksum_));
}

std::size_t StateWriter::stored(const std::string&, Type) { throw std::logic_error("StateWriter: not loading"); }
void StateWriter::load(const std::string&, Type, void*, std::size_t) {
  throw std::logic_error("StateWriter: not loading");
}
std::string StateWriter::where(const std::string& name) const { return group_.where(name); }

// ---------------------------------------------------------------- StateReader

StateReader::StateReader(const Group& group) : where_(group.where()) {
  if (!group.has(kEntries) || !group.has_attr("checksum"))
    throw InputError(where_ + ": not a checkpoint's state (no list of entries or no checksum)");
  EntryChecksum c;
  for (const std::string& line : group.read_strings(kEntries)) {
    const std::size_t space = line.find(' ');
    const std::string type_name = line.substr(0, space),
                      name = space == std::string::npos ? "" : line.substr(space + 1);
    int type = -1;
    for (int t = 0; t < 3; ++t)
      if (type_name == kTypeName[t]) type = t;
    if (type < 0 || name.empty()) throw InputError(where_ + ": damaged list of entries ('" + line + "')");
    Entry e{static_cast<Type>(type), {}};
    auto take = [&](const auto& values) {
      e.bytes.resize(values.size() * kTypeBytes[type]);
      if (!values.empty()) std::memcpy(e.bytes.data(), values.data(), e.bytes.size());
      c.add_entry(name, type, values.data(), values.size(), kTypeBytes[type]);
    };
    if (type == 0)
      take(group.read<double>(name, nullptr, 1));
    else if (type == 1)
      take(group.read<std::int64_t>(name, nullptr, 1));
    else
      take(group.read<std::uint8_t>(name, nullptr, 1));
    entries_[name] = std::move(e);
  }
  if (static_cast<std::int64_t>(c.h) != group.attr_int("checksum"))
    throw InputError(where_ + ": damaged checkpoint (the state does not match its checksum)");
}

std::size_t StateReader::stored(const std::string& name, Type type) {
  const auto it = entries_.find(name);
  if (it == entries_.end()) throw InputError(where(name) + ": missing from the checkpoint");
  if (it->second.type != type)
    throw InputError(where(name) + ": holds " + kTypeName[static_cast<int>(it->second.type)] + ", expected " +
                     kTypeName[static_cast<int>(type)]);
  return it->second.bytes.size() / kTypeBytes[static_cast<int>(type)];
}

void StateReader::load(const std::string& name, Type type, void* data, std::size_t count) {
  const Entry& e = entries_.at(name);
  if (count > 0) std::memcpy(data, e.bytes.data(), count * kTypeBytes[static_cast<int>(type)]);
}

void StateReader::save(const std::string&, Type, const void*, std::size_t) {
  throw std::logic_error("StateReader: not saving");
}
std::string StateReader::where(const std::string& name) const { return where_ + "/" + name; }

// ---------------------------------------------------------------- run identity

std::string run_key(const ToolRun& run) {
  std::ostringstream key;
  key << "tool=" << run.tool << "\nversion=" << kVersion << "\nseed=" << run.seed << "\n";
  for (const auto& [name, value] : run.parameters)
    if (name != "scene") key << name << "=" << value << "\n";
  for (const std::string& uuid : run.input_uuids) key << "input=" << uuid << "\n";
  return key.str();
}

// ---------------------------------------------------------------- Checkpoints

Checkpoints::Checkpoints(const CheckpointOptions& options, std::string path, const ToolRun& run, RunWriter* writer,
                         std::string last_path, std::int64_t last_step)
    : options_(options),
      path_(std::move(path)),
      run_(run),
      key_(run_key(run)),
      writer_(writer),
      last_time_(std::chrono::steady_clock::now()),
      last_path_(std::move(last_path)),
      last_step_(last_step) {}

std::string Checkpoints::stopped_note(std::int64_t step) const {
  std::string note = "the run stopped" + (step >= 0 ? " after step " + std::to_string(step) : std::string());
  if (!enabled() && last_path_.empty())
    return note + "; it wrote no checkpoints (its output is not a file: --checkpoint FILE gives it some)";
  if (last_path_.empty()) return note + "; no checkpoint of it was written before: run again, it starts afresh";
  return note + "; its last checkpoint, " + last_path_ + " (step " + std::to_string(last_step_) +
         "), is intact: the same command line continues from it";
}

bool Checkpoints::due(std::int64_t step) const {
  if (!enabled()) return false;
  if (options_.every_steps > 0 && step % options_.every_steps == 0) return true;
  return options_.every_seconds > 0 &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - last_time_).count() >= options_.every_seconds;
}

void Checkpoints::write(std::int64_t step, double time, const std::function<void(StateArchive&)>& visit) {
  const auto start = std::chrono::steady_clock::now();
  try {
    OutputFile out(path_);
    write_header(out.root(), "checkpoint", run_, out.uuid());
    out.root().set_attr("run_key", key_);
    out.root().set_attr("step", static_cast<std::int64_t>(step));
    out.root().set_attr("time", time);
    Group run = out.root().create_group("run");
    if (writer_) writer_->copy_progress(run);
    StateWriter state(out.root().create_group("state"));
    visit(state);
    state.finish();
    out.commit(true);
  } catch (const RuntimeError& e) {
    throw RunStopped("cannot write the checkpoint: " + std::string(e.what()) + "; " + stopped_note(step));
  }
  last_path_ = path_;
  last_step_ = step;
  last_time_ = std::chrono::steady_clock::now();
  ++written_;
  seconds_ += std::chrono::duration<double>(last_time_ - start).count();
}

void Checkpoints::remove() {
  if (!enabled()) return;
  std::error_code ec;
  std::filesystem::remove(path_, ec);
  remove_abandoned_temps(path_);  // of a checkpoint a killed run was writing
}

void Checkpoints::stop_if_signalled(std::int64_t step, double time, const std::function<void(StateArchive&)>& visit) {
  const int sig = stop_signal();
  if (sig == 0) return;
  std::ostringstream msg;
  msg << "stopped by "
      << (sig == SIGTERM  ? "SIGTERM"
          : sig == SIGINT ? "SIGINT"
                          : "SIGHUP")
      << " after step " << step << " (t = " << time << " s)";
  if (enabled()) {
    try {
      write(step, time, visit);
    } catch (const RunStopped& e) {
      throw RunStopped(msg.str() + "; " + e.what());
    }
    msg << "; checkpoint " << path_ << " written: the same command line continues the run";
  } else {
    msg << "; no checkpoint (the output is standard output: give --checkpoint FILE)";
  }
  throw Interrupted(sig, msg.str());
}

// ---------------------------------------------------------------- Resume

std::optional<Resume> Resume::find(const CheckpointOptions& options, const std::string& path, ToolRun& run,
                                   const std::function<void(const std::string&)>& warn) {
  const bool explicit_resume = !options.resume.empty();
  const std::string file = explicit_resume ? options.resume : path;
  if (file.empty()) return std::nullopt;
  std::error_code ec;
  if (!explicit_resume && !std::filesystem::exists(file, ec)) return std::nullopt;
  Resume r;
  r.path_ = file;
  r.root_.emplace(open_input(file));
  check_header(*r.root_, {"checkpoint"});
  const std::string key = r.root_->attr_string("run_key"), ours = run_key(run);
  if (key != ours) {
    // The first line that differs names the culprit.
    std::istringstream a(key), b(ours);
    std::string la, lb;
    while (std::getline(a, la) && std::getline(b, lb) && la == lb) {
    }
    const std::string why = file + ": a checkpoint of another run (it has '" + la + "', this run '" + lb + "')";
    if (explicit_resume) throw InputError(why);
    warn(why + "; starting afresh, the checkpoint will be replaced");
    return std::nullopt;
  }
  r.step_ = r.root_->attr_int("step");
  if (r.step_ < 0) throw InputError(r.root_->where() + ": negative step attribute");
  r.run_.emplace(r.root_->group("run"));
  r.state_ = std::make_unique<StateReader>(r.root_->group("state"));
  run.segments = read_segments(*r.root_);
  run.segments.push_back({run.started, run.command_line, r.step_});
  return r;
}

// ---------------------------------------------------------------- RunCheckpoints

namespace {

// The checkpoint file of a run writing `output`, checked before the run: a file (links resolved) in a folder
// the run can write to; none by default when the output is not a file (standard output, a device, a FIFO).
std::string checked_checkpoint_path(const CheckpointOptions& options, const std::string& output) {
  if (options.path.empty() && (output == "-" || resolve_output(output).kind != OutputKind::file)) return "";
  const std::string path = checkpoint_path(options, output);
  const OutputTarget target = resolve_output(path);
  if (target.kind != OutputKind::file)
    throw UsageError("--checkpoint " + path + ": a checkpoint is a file, not standard output, a device or a FIFO");
  try {
    AtomicFile probe(target.path);  // (a temporary made and removed: the folder takes files)
  } catch (const UsageError& e) {
    throw UsageError("--checkpoint: " + std::string(e.what()));
  } catch (const RuntimeError& e) {
    throw RuntimeError("--checkpoint: " + std::string(e.what()));
  }
  return target.path;
}

}  // namespace

RunCheckpoints::RunCheckpoints(const CheckpointOptions& options, const std::string& output, ToolRun& run,
                               const std::function<void(const std::string&)>& note)
    : options_(options),
      path_(checked_checkpoint_path(options, output)),
      run_(run),
      note_(note),
      resume_(Resume::find(options, path_, run, note)) {}

Continuation RunCheckpoints::start(RunWriter& writer) {
  checkpoints_.emplace(options_, path_, run_, &writer, resume_ ? resume_->path() : "", resume_ ? resume_->step() : -1);
  Continuation c{&*checkpoints_, nullptr};
  if (resume_) {
    note_("continuing from " + resume_->path() + " at step " + std::to_string(resume_->step()));
    writer.replay(resume_->output());
    c.resume = &resume_->state();
  }
  return c;
}

}  // namespace frac::io
