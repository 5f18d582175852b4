#include "core/team_barrier.hpp"

#include <omp.h>

#include <climits>
#include <thread>

#if defined(__linux__)
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace frac {
namespace {

// Spins before sleeping: ~0.3-1 ms of pause instructions with a core for each thread (longer than any wait
// inside a force evaluation: no system call in the steady state); a few µs when threads share cores, where the
// one awaited may need the core of the one spinning.
constexpr std::uint32_t kSpinsOwnCore = 20000;
constexpr std::uint32_t kSpinsSharedCores = 64;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Sleeps while *word == expected (or returns at once when it is not).
void sleep_while(std::atomic<std::uint32_t>& word, std::uint32_t expected) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, expected, nullptr, nullptr, 0);
#else
  (void)word, (void)expected;
  std::this_thread::yield();
#endif
}

void wake_all(std::atomic<std::uint32_t>& word) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
#else
  (void)word;
#endif
}

}  // namespace

static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t) &&
              std::atomic<std::uint32_t>::is_always_lock_free);

TeamBarrier::TeamBarrier(unsigned threads, unsigned cores)
    : threads_(threads == 0 ? 1 : threads), spins_(threads > cores ? kSpinsSharedCores : kSpinsOwnCore) {}

void TeamBarrier::wait() {
  if (threads_ == 1) return;
  // (The generation cannot move on before this thread arrives: the value read is this barrier's.)
  const std::uint32_t generation = generation_.load(std::memory_order_acquire);
  // Release: what this thread wrote goes with its arrival; acquire: the last to arrive sees what all wrote.
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
    arrived_.store(0, std::memory_order_relaxed);  // (ordered before the release below: seen by the next barrier)
    generation_.store(generation + 1, std::memory_order_seq_cst);
    // A sleeper counts itself (seq_cst) before it reads the generation: either it sees the new one, or this
    // load sees it counted and wakes it.
    if (sleepers_.load(std::memory_order_seq_cst) != 0) wake_all(generation_);
    return;
  }
  for (std::uint32_t s = 0; s < spins_; ++s) {
    if (generation_.load(std::memory_order_acquire) != generation) return;
    cpu_relax();
  }
  sleepers_.fetch_add(1, std::memory_order_seq_cst);
  while (generation_.load(std::memory_order_seq_cst) == generation) sleep_while(generation_, generation);
  sleepers_.fetch_sub(1, std::memory_order_relaxed);
}

TeamBarrier*& detail::current_team_barrier() {
  thread_local TeamBarrier* barrier = nullptr;
  return barrier;
}

void team_barrier() {
  if (TeamBarrier* barrier = detail::current_team_barrier()) {
    barrier->wait();
    return;
  }
#pragma omp barrier
}

}  // namespace frac
