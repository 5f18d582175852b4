#pragma once
// The barrier of the force loops' teams (core/parallel.hpp: as_team). OpenMP's barrier in GCC's libgomp ends
// with a futex wake, a system call, whether or not a thread sleeps, several times the cost of a barrier that
// only spins (bench/team_barrier.cpp), and a DEM step has five to seven of them. This
// one spins on a generation count, and a thread that has spun long (a team larger than the cores, a thread
// descheduled) sleeps on a futex, which the last to arrive wakes only when someone sleeps.
#include <atomic>
#include <cstdint>

#include "core/spin_wait.hpp"

namespace frac {

class TeamBarrier {
 public:
  // For a team of `threads`, run on `cores` processors (more threads than cores: spin briefly, then sleep).
  TeamBarrier(unsigned threads, unsigned cores);
  TeamBarrier(const TeamBarrier&) = delete;
  TeamBarrier& operator=(const TeamBarrier&) = delete;
  // Returns when every thread of the team has called it (the n-th time for every thread): what each wrote
  // before is visible to all after.
  void wait();

 private:
  alignas(64) std::atomic<std::uint32_t> arrived_{0};
  alignas(64) spin::WaitCount generation_;
  unsigned threads_;
  std::uint32_t spins_;
};

// Inside a team function: the barrier of the team as_team runs it on (core/thread_team.hpp); OpenMP's inside an
// OpenMP region; nothing outside both.
void team_barrier();

}  // namespace frac
