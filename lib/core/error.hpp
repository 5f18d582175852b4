#pragma once
// Typed errors. The library throws; only a tool's main prints and picks the exit code:
// UsageError and InputError -> exit 2 (bad usage or bad input), anything else -> exit 1.
#include <stdexcept>
#include <string>

namespace frac {

// Bad command line: an unknown option, a value out of range, a missing argument.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input data: a missing or unreadable file, a file of the wrong kind, a failed invariant.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A failure while running on valid input (I/O error on output, numerical breakdown).
struct RuntimeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A run stopped by a stop signal (core/signals: SIGTERM at a batch job's time limit, SIGINT) after it wrote
// what it could (its checkpoint): the tool reports it and ends by that signal.
struct Interrupted : std::runtime_error {
  Interrupted(int sig, const std::string& what) : std::runtime_error(what), signal(sig) {}
  int signal;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace frac
