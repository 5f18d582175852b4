#pragma once
// Atomic HDF5 output. A named file is written under a temporary name in the same folder and renamed
// into place by commit(); standard output ("-") and devices or FIFOs (io/output_target) get a file built in
// memory (HDF5 core driver), whose image commit() writes. Without commit() (an exception, a signal) nothing
// appears: a crash never leaves a half-written file that Make would take as done.
#include <optional>
#include <string>

#include <memory>

#include "io/atomic_file.hpp"
#include "io/hdf5.hpp"
#include "io/output_target.hpp"

namespace frac::io {

class OutputFile {
 public:
  // Throws UsageError when the output is a terminal, or the folder is missing.
  explicit OutputFile(std::string path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();

  Group& root() { return *root_; }
  const std::string& path() const { return path_; }
  // The new file's identity, recorded in /provenance.
  const std::string& uuid() const { return uuid_; }

  // Closes the file and makes it appear (rename, or the image written to standard output); `durable`: on the
  // disk before it appears (a checkpoint that must survive a node failure).
  void commit(bool durable = false);

 private:
  std::string path_;
  std::unique_ptr<AtomicFile> atomic_;    // the temporary file of a file
  std::unique_ptr<OutputStream> stream_;  // a device or FIFO
  std::string uuid_;
  Hid file_;
  std::optional<Group> root_;
  bool committed_ = false;
};

}  // namespace frac::io
