#pragma once
// Where a named output goes. A regular file, or a name not yet taken, is written under a temporary name and
// renamed onto it (io/atomic_file); through a symbolic link, the link stays and its target is replaced, as cp
// writes through one. A character device (/dev/null, /dev/full, a terminal) or a FIFO is written in place, as
// cp does: never replaced by a regular file. "-", or a name that is standard output itself (/dev/stdout, or
// the file standard output was redirected to), is standard output. A folder, a socket or a block device is
// refused.
#include <cstddef>
#include <string>

namespace frac::io {

enum class OutputKind { standard_output, file, stream };

struct OutputTarget {
  OutputKind kind;
  std::string path;  // file: the file to replace (links resolved); stream: the device or FIFO; else "-"
};

// UsageError naming `path` for an empty name, a folder, a socket or a block device.
OutputTarget resolve_output(const std::string& path);

// A device or FIFO opened for writing when constructed: RuntimeError when it cannot be (a FIFO no process
// reads: no hang), UsageError for a terminal when `binary`.
class OutputStream {
 public:
  OutputStream(std::string path, bool binary);
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;
  ~OutputStream();
  // RuntimeError naming the stream when not every byte could be written (/dev/full: no space left).
  void write(const void* data, std::size_t size);

 private:
  std::string path_;
  int fd_ = -1;
};

// Writes `size` bytes to standard output and flushes it: RuntimeError when not every byte could be written.
void write_standard_output(const void* data, std::size_t size);

}  // namespace frac::io
