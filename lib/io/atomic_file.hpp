#pragma once
// Atomic output, for every file a tool writes: a temporary name in the target's folder
// (".NAME.tmp-XXXXXX", hidden), renamed onto the target by commit(). Without commit() (an exception,
// SIGINT/SIGTERM/SIGHUP) the temporary file is removed and the target is left as it was: a crash never
// leaves a half-written file that Make would take as done. The writer holds an exclusive lock (flock) on
// its temporary file while it lives; a process killed outright (SIGKILL, a node failure) leaves its
// temporary unlocked, and the next writer of the same target removes every unlocked temporary of it, so
// temporaries never accumulate. io/output_file builds HDF5 outputs on it.
#include <string>

namespace frac::io {

class AtomicFile {
 public:
  // UsageError when the target's folder does not exist or the name is empty; RuntimeError when the
  // temporary file cannot be created.
  explicit AtomicFile(std::string target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  const std::string& path() const { return temp_; }  // write here
  const std::string& target() const { return target_; }
  void commit(bool durable = false);  // rename onto the target; `durable`: synced to the disk first

 private:
  std::string target_, temp_;
  int fd_ = -1;  // holds the lock
  bool committed_ = false;
};

// Why a write to `path` may have failed, for messages: the file size limit (EFBIG under ulimit -f), "the disk
// is full" when its file system has no space left, else the system's message for `error` (an errno value).
std::string write_failure(const std::string& path, int error);

// Removes the temporaries of `target` that no process holds locked: left by a killed writer.
void remove_abandoned_temps(const std::string& target);

// Writes `text` to `path` atomically; to standard output or a device as io/output_target resolves `path`.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace frac::io
