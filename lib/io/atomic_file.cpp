#include "io/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "core/signals.hpp"
#include "io/output_target.hpp"

namespace frac::io {
namespace {

// Temporary files to remove if the process is interrupted. A fixed table of C strings: the handler
// may only call async-signal-safe functions.
constexpr int kMaxTemps = 16;
char g_temps[kMaxTemps][4096];
volatile std::sig_atomic_t g_used[kMaxTemps];

// Async-signal-safe: called from the stop-signal handler (core/signals).
void remove_temps() {
  for (int k = 0; k < kMaxTemps; ++k)
    if (g_used[k]) unlink(g_temps[k]);
}

void register_temp(const std::string& path) {
  on_stop_signal(remove_temps);
  for (int k = 0; k < kMaxTemps; ++k) {
    if (!g_used[k] && path.size() < sizeof g_temps[k]) {
      std::memcpy(g_temps[k], path.c_str(), path.size() + 1);
      g_used[k] = 1;
      return;
    }
  }
}

void unregister_temp(const std::string& path) {
  for (int k = 0; k < kMaxTemps; ++k)
    if (g_used[k] && path == g_temps[k]) g_used[k] = 0;
}

// Removes the temporaries of `name` in `dir` that no process holds locked: left by a killed writer.
void remove_abandoned_in(const std::filesystem::path& dir, const std::string& name) {
  const std::string prefix = "." + name + ".tmp-";
  DIR* d = opendir(dir.c_str());
  if (!d) return;
  while (const dirent* e = readdir(d)) {
    if (std::strncmp(e->d_name, prefix.c_str(), prefix.size()) != 0) continue;
    const std::string path = (dir / e->d_name).string();
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) continue;
    struct stat opened {
    }, named{};
    // Unlocked and still the file of that name: abandoned.
    if (flock(fd, LOCK_EX | LOCK_NB) == 0 && fstat(fd, &opened) == 0 && lstat(path.c_str(), &named) == 0 &&
        opened.st_ino == named.st_ino && opened.st_dev == named.st_dev && S_ISREG(named.st_mode))
      unlink(path.c_str());
    close(fd);
  }
  closedir(d);
}

}  // namespace

void remove_abandoned_temps(const std::string& target) {
  const std::filesystem::path t(target);
  remove_abandoned_in(t.has_parent_path() ? t.parent_path() : std::filesystem::path("."), t.filename().string());
}

std::string write_failure(const std::string& path, int error) {
  struct rlimit limit {};
  if (error == EFBIG && getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    return "the file size limit is reached (ulimit -f: " + std::to_string(limit.rlim_cur) + " bytes)";
  if (path == "-") return error != 0 ? std::strerror(error) : "write error";
  const std::filesystem::path p(path);
  const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
  struct statvfs fs {};
  if (statvfs(dir.c_str(), &fs) == 0 && fs.f_bavail == 0) return "the disk is full";
  return error != 0 ? std::strerror(error) : "write error";
}

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
  if (target_.empty()) throw UsageError("--output: empty file name");
  const std::filesystem::path t(target_);
  const auto dir = t.has_parent_path() ? t.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw UsageError(target_ + ": folder '" + dir.string() + "' does not exist");
  if (t.filename().empty() || std::filesystem::is_directory(t, ec))
    throw UsageError(target_ + ": is a folder, not a file name");
  remove_abandoned_in(dir, t.filename().string());
  std::string name = (dir / ("." + t.filename().string() + ".tmp-XXXXXX")).string();
  std::vector<char> buf(name.begin(), name.end());
  buf.push_back('\0');
  fd_ = mkostemp(buf.data(), O_CLOEXEC);
  if (fd_ < 0)
    throw RuntimeError(target_ + ": cannot create a file in '" + dir.string() + "' (" + write_failure(target_, errno) +
                       ")");
  temp_ = buf.data();
  register_temp(temp_);
  flock(fd_, LOCK_EX);  // ours: not abandoned (the lock goes with the process)
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) close(fd_);
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove(temp_, ec);
  unregister_temp(temp_);
}

void AtomicFile::commit(bool durable) {
  if (committed_) return;
  if (durable && fsync(fd_) != 0)
    throw RuntimeError(target_ + ": cannot write the file to the disk (" + write_failure(target_, errno) + ")");
  std::error_code ec;
  // mkstemp makes the file 0600; give it the permissions a new file normally gets.
  const mode_t mask = umask(0);
  umask(mask);
  std::filesystem::permissions(temp_, static_cast<std::filesystem::perms>(0666 & ~mask), ec);
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw RuntimeError(target_ + ": cannot move the finished file into place: " + ec.message());
  unregister_temp(temp_);
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const OutputTarget target = resolve_output(path);
  if (target.kind == OutputKind::standard_output) return write_standard_output(text.data(), text.size());
  if (target.kind == OutputKind::stream) return OutputStream(target.path, false).write(text.data(), text.size());
  AtomicFile file(target.path);
  {
    std::FILE* f = std::fopen(file.path().c_str(), "wb");
    if (!f) throw RuntimeError(path + ": cannot write the file (" + write_failure(path, errno) + ")");
    bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    int error = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) ok = false, error = errno;
    if (!ok) throw RuntimeError(path + ": cannot write the file (" + write_failure(path, error) + ")");
  }
  file.commit();
}

}  // namespace frac::io
