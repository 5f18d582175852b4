#include "core/progress.hpp"

#include <unistd.h>
#include <cstdio>
#include <iostream>

namespace frac {

Progress::Progress(std::string tool, bool quiet, double interval_s)
    : tool_(std::move(tool)),
      quiet_(quiet),
      tty_(isatty(STDERR_FILENO) != 0),
      interval_(interval_s),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() {
  if (live_) std::cerr << "\n";
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::tick(const std::function<std::string()>& line) {
  if (quiet_ || (++counter_ & 63u) != 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (since < (tty_ ? 0.2 : interval_)) return;
  last_ = now;
  if (tty_) {
    std::cerr << "\r\033[K" << tool_ << ": " << line() << std::flush;
    live_ = true;
  } else {
    std::cerr << tool_ << ": " << line() << "\n" << std::flush;
  }
}

void Progress::note(const std::string& message) {
  if (quiet_) return;
  if (live_) std::cerr << "\r\033[K";
  live_ = false;
  std::cerr << tool_ << ": " << message << "\n" << std::flush;
}

void Progress::finish(const std::string& last) {
  if (quiet_) return;
  if (live_) std::cerr << "\r\033[K";
  live_ = false;
  if (!last.empty()) std::cerr << tool_ << ": " << last << "\n" << std::flush;
}

}  // namespace frac
