#include "io/output_target.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"

namespace frac::io {
namespace {

// The name a chain of symbolic links ends at (a dangling link: the file it would create), at most 40 deep
// as the kernel allows; `path` itself when it is no link.
std::string follow_links(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  for (int depth = 0; depth < 40; ++depth) {
    std::error_code ec;
    if (!fs::is_symlink(p, ec)) return p.string();
    const fs::path next = fs::read_symlink(p, ec);
    if (ec) return p.string();
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  throw UsageError(path + ": too many levels of symbolic links");
}

bool is_standard_output(const struct stat& st) {
  struct stat out {};
  return fstat(STDOUT_FILENO, &out) == 0 && out.st_dev == st.st_dev && out.st_ino == st.st_ino;
}

}  // namespace

OutputTarget resolve_output(const std::string& path) {
  if (path.empty()) throw UsageError("--output: empty file name");
  if (path == "-") return {OutputKind::standard_output, "-"};
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return {OutputKind::file, follow_links(path)};  // a new file
  if (is_standard_output(st)) return {OutputKind::standard_output, "-"};
  if (S_ISREG(st.st_mode)) return {OutputKind::file, follow_links(path)};
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {OutputKind::stream, path};
  if (S_ISDIR(st.st_mode)) throw UsageError(path + ": is a folder, not a file name");
  throw UsageError(path + ": is a " + std::string(S_ISSOCK(st.st_mode) ? "socket" : "block device") +
                   ", not a file an output can go to");
}

OutputStream::OutputStream(std::string path, bool binary) : path_(std::move(path)) {
  // Non-blocking, so that a FIFO no process reads fails at once (ENXIO) instead of waiting for a reader.
  fd_ = open(path_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0)
    throw RuntimeError(path_ + ": cannot write to it (" +
                       (errno == ENXIO ? std::string("a FIFO that no process reads") : std::strerror(errno)) + ")");
  fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
  if (binary && isatty(fd_)) {
    close(fd_);
    fd_ = -1;
    throw UsageError(path_ + ": refusing to write an HDF5 file to a terminal");
  }
}

OutputStream::~OutputStream() {
  if (fd_ >= 0) close(fd_);
}

void OutputStream::write(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw RuntimeError(path_ + ": cannot write to it (" + std::strerror(n < 0 ? errno : EIO) + ")");
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void write_standard_output(const void* data, std::size_t size) {
  if (std::fwrite(data, 1, size, stdout) != size || std::fflush(stdout) != 0)
    throw RuntimeError("-: cannot write to standard output (" + std::string(std::strerror(errno)) + ")");
}

}  // namespace frac::io
