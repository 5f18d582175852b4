#include "core/signals.hpp"

#include <unistd.h>

#include <mutex>

namespace frac {
namespace {

constexpr int kMaxHooks = 8;
void (*volatile g_hooks[kMaxHooks])() = {};
volatile std::sig_atomic_t g_deferred = 0;  // DeferSignals alive
volatile std::sig_atomic_t g_noted = 0;     // the signal noted while deferred

void run_hooks() {
  for (int k = 0; k < kMaxHooks; ++k)
    if (g_hooks[k]) g_hooks[k]();
}

extern "C" void on_signal(int sig) {
  if (g_deferred && !g_noted) {
    g_noted = sig;
    return;
  }
  run_hooks();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, on_signal);
  });
}

}  // namespace

void on_stop_signal(void (*cleanup)()) {
  install();
  for (int k = 0; k < kMaxHooks; ++k) {
    if (g_hooks[k] == cleanup) return;
    if (!g_hooks[k]) {
      g_hooks[k] = cleanup;
      return;
    }
  }
}

DeferSignals::DeferSignals() {
  install();
  g_deferred = 1;
}

DeferSignals::~DeferSignals() { g_deferred = 0; }

void run_cleanup_hooks() { run_hooks(); }

int stop_signal() { return g_noted; }

void die_by_signal(int sig) {
  run_hooks();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
  _exit(128 + sig);  // (a blocked signal)
}

}  // namespace frac
