#pragma once
// Progress of a long run on stderr: a live line (rewritten in place) when stderr is a terminal, a
// plain line every few seconds when it is a log, nothing when quiet. The caller supplies the line.
#include <chrono>
#include <functional>
#include <string>

namespace frac {

class Progress {
 public:
  // `interval_s`: seconds between lines in a log (a terminal is refreshed every 0.2 s).
  Progress(std::string tool, bool quiet, double interval_s = 5.0);
  ~Progress();
  // Cheap to call every step: looks at the clock every 64 calls, then asks `line` for the text.
  void tick(const std::function<std::string()>& line);
  // A line of its own, "tool: message" (if not quiet).
  void note(const std::string& message);
  // Ends a live line (and prints `last` if not quiet).
  void finish(const std::string& last);
  double elapsed() const;  // s since construction

 private:
  std::string tool_;
  bool quiet_, tty_;
  double interval_;
  unsigned counter_ = 0;
  bool live_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace frac
