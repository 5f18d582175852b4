#include "core/team_barrier.hpp"

#include "core/thread_team.hpp"

namespace frac {

TeamBarrier::TeamBarrier(unsigned threads, unsigned cores)
    : threads_(threads == 0 ? 1 : threads), spins_(spin::spins(threads, cores)) {}

void TeamBarrier::wait() {
  if (threads_ == 1) return;
  // (The generation cannot move on before this thread arrives: the value read is this barrier's.)
  const std::uint32_t generation = generation_.now();
  // Release: what this thread wrote goes with its arrival; acquire: the last to arrive sees what all wrote.
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
    arrived_.store(0, std::memory_order_relaxed);  // (ordered before the advance: seen by the next barrier)
    generation_.advance();
    return;
  }
  generation_.wait_past(generation, spins_);
}

void team_barrier() {
  if (TeamBarrier* barrier = team_member().barrier) {
    barrier->wait();
    return;
  }
#pragma omp barrier
}

}  // namespace frac
