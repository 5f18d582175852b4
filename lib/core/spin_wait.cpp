#include "core/spin_wait.hpp"

#include <cctype>
#include <climits>
#include <cstdlib>
#include <string>
#include <thread>

#if defined(__linux__)
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace frac::spin {

static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t) &&
              std::atomic<std::uint32_t>::is_always_lock_free);

namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Sleeps while word == expected (returns at once when it is not; may return early: the caller checks again).
void sleep_while(std::atomic<std::uint32_t>& word, std::uint32_t expected) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, expected, nullptr, nullptr, 0);
#else
  (void)word, (void)expected;
  std::this_thread::yield();
#endif
}

// Wakes every thread sleeping on word.
void wake_all(std::atomic<std::uint32_t>& word) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
#else
  (void)word;
#endif
}

}  // namespace

bool passive_wait_policy() {
  static const bool passive = [] {
    const char* policy = std::getenv("OMP_WAIT_POLICY");
    if (!policy) return false;
    std::string value(policy);
    for (char& c : value) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return value == "passive";
  }();
  return passive;
}

void WaitCount::advance() {
  // seq_cst, with the sleeper's count below: either the sleeper sees the new count, or this load sees it
  // counted and wakes it.
  count_.fetch_add(1, std::memory_order_seq_cst);
  if (sleepers_.load(std::memory_order_seq_cst) != 0) wake_all(count_);
}

std::uint32_t WaitCount::wait_past(std::uint32_t seen, std::uint32_t spins) {
  std::uint32_t now = count_.load(std::memory_order_acquire);
  for (std::uint32_t s = 0; now == seen && s < spins; ++s) {
    cpu_relax();
    now = count_.load(std::memory_order_acquire);
  }
  if (now != seen) return now;
  sleepers_.fetch_add(1, std::memory_order_seq_cst);
  while ((now = count_.load(std::memory_order_seq_cst)) == seen) sleep_while(count_, seen);
  sleepers_.fetch_sub(1, std::memory_order_relaxed);
  return now;
}

}  // namespace frac::spin
