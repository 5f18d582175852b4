#pragma once
// SIGINT, SIGTERM and SIGHUP. By default one ends the process at once, after the cleanup hooks (async-signal-safe
// functions: io/atomic_file removes its temporaries), by the same signal. A run loop that can stop cleanly defers
// them while it runs (DeferSignals): the first signal is only noted, and the loop asks stop_signal() between
// steps, writes its checkpoint and unwinds; a second signal acts at once.
#include <csignal>

namespace frac {

// Installs the handlers (once) and adds `cleanup` to the hooks (at most 8).
void on_stop_signal(void (*cleanup)());

// While one lives, a stop signal is noted, not acted on.
class DeferSignals {
 public:
  DeferSignals();
  ~DeferSignals();
  DeferSignals(const DeferSignals&) = delete;
  DeferSignals& operator=(const DeferSignals&) = delete;
};

// Runs the cleanup hooks (async-signal-safe): for a process that ends otherwise than by a signal or exit().
void run_cleanup_hooks();

// The signal noted while deferred, or 0.
int stop_signal();

// Ends the process by `sig` (after the cleanup hooks), as the default action would.
[[noreturn]] void die_by_signal(int sig);

}  // namespace frac
