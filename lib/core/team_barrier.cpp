#include "core/team_barrier.hpp"

#include "core/spin_wait.hpp"
#include "core/thread_team.hpp"

namespace frac {

TeamBarrier::TeamBarrier(unsigned threads, unsigned cores)
    : threads_(threads == 0 ? 1 : threads), spins_(spin::spins(threads, cores)) {}

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
    if (sleepers_.load(std::memory_order_seq_cst) != 0) spin::wake_all(generation_);
    return;
  }
  for (std::uint32_t s = 0; s < spins_; ++s) {
    if (generation_.load(std::memory_order_acquire) != generation) return;
    spin::cpu_relax();
  }
  sleepers_.fetch_add(1, std::memory_order_seq_cst);
  while (generation_.load(std::memory_order_seq_cst) == generation) spin::sleep_while(generation_, generation);
  sleepers_.fetch_sub(1, std::memory_order_relaxed);
}

void team_barrier() {
  if (TeamBarrier* barrier = team_member().barrier) {
    barrier->wait();
    return;
  }
#pragma omp barrier
}

}  // namespace frac
