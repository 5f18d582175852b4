#pragma once
// Waiting on a count shared by threads: pauses in a spin loop, then sleeping until the count moves on (a futex on
// Linux; elsewhere a yield, and a loop). For the team barrier and the thread team.
#include <atomic>
#include <cstdint>

namespace frac::spin {

// Spins before sleeping: ~0.3-1 ms of pause instructions with a core for each thread (longer than any wait
// inside a force evaluation or between two: no system call in the steady state); a few µs when threads share
// cores, where the one awaited may need the core of the one spinning; none with OMP_WAIT_POLICY=passive (as
// OpenMP's threads: for runs side by side, where a spinning thread takes a core another job needs).
inline constexpr std::uint32_t kSpinsOwnCore = 20000;
inline constexpr std::uint32_t kSpinsSharedCores = 64;
bool passive_wait_policy();  // OMP_WAIT_POLICY is "passive" (any case), read once
inline std::uint32_t spins(unsigned threads, unsigned cores) {
  if (passive_wait_policy()) return 0;
  return threads > cores ? kSpinsSharedCores : kSpinsOwnCore;
}

// A count that threads wait on (a barrier's generation, a team's next run): waiters spin, then sleep, until it
// moves on; the one that moves it wakes the sleepers, and makes no system call when none sleeps.
class WaitCount {
 public:
  std::uint32_t now() const { return count_.load(std::memory_order_acquire); }
  // Moves the count on by one (what the caller wrote before goes with it) and wakes the sleepers, if any.
  void advance();
  // Returns the count once it is no longer `seen` (what the advancing thread wrote before is visible): spins
  // `spins` times, then sleeps.
  std::uint32_t wait_past(std::uint32_t seen, std::uint32_t spins);

 private:
  std::atomic<std::uint32_t> count_{0};
  std::atomic<std::uint32_t> sleepers_{0};
};

}  // namespace frac::spin
