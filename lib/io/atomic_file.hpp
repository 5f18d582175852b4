#pragma once
// Atomic output, for every file a tool writes: a temporary name in the target's folder
// (".NAME.tmp-XXXXXX", hidden), renamed onto the target by commit(). Without commit() (an exception,
// SIGINT/SIGTERM/SIGHUP) the temporary file is removed and the target is left as it was: a crash never
// leaves a half-written file that Make would take as done. io/output_file builds HDF5 outputs on it.
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
  void commit();  // rename onto the target

 private:
  std::string target_, temp_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically; "-" writes it to standard output.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace frac::io
