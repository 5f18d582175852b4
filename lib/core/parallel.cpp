#include "core/parallel.hpp"

#include <omp.h>

#include <string>
#include <system_error>

#include "core/error.hpp"
#include "core/float_mode.hpp"

namespace frac {

int max_threads() { return omp_get_max_threads(); }
int thread_count() {
  const TeamMember& me = team_member();
  return me.count != 0 ? static_cast<int>(me.count) : omp_get_num_threads();
}
int thread_index() {
  const TeamMember& me = team_member();
  return me.count != 0 ? static_cast<int>(me.index) : omp_get_thread_num();
}
bool in_parallel() { return team_member().count > 1 || omp_in_parallel() != 0; }
unsigned processor_count() { return static_cast<unsigned>(omp_get_num_procs()); }

void run_as_team(ThreadTeam::Job job, void* body) {
  ThreadTeam& team = ThreadTeam::shared();
  const auto threads = static_cast<unsigned>(max_threads());
  if (team.size() != threads) team.resize(threads, processor_count());
  team.run(job, body);
}

void HomeFirstSchedule::reserve(std::size_t threads) {
  if (threads <= capacity_) return;
  cursor_ = std::make_unique<Cursor[]>(threads);
  capacity_ = threads;
}

void HomeFirstSchedule::set(std::size_t t, std::size_t items, std::size_t nt) {
  const Range r = static_range(items, t, nt);
  cursor_[t].first = r.first;
  cursor_[t].end = r.last;
  cursor_[t].span.store(static_cast<std::uint64_t>(r.last - r.first), std::memory_order_relaxed);
}

void HomeFirstSchedule::start_mine(std::size_t items) {
  set(static_cast<std::size_t>(thread_index()), items, static_cast<std::size_t>(thread_count()));
}

void HomeFirstSchedule::reset(std::size_t items, std::size_t nt) {
  for (std::size_t t = 0; t < nt; ++t) set(t, items, nt);
}

PartLayout::PartLayout(std::size_t n, std::size_t blocks, std::size_t threads)
    : n_(n), blocks_(blocks == 0 || n % blocks != 0 ? 1 : blocks), threads_(threads == 0 ? 1 : threads) {
  len_ = n_ / blocks_;
  gap_ = threads_ > 1 ? kPartGap : 0;
}

std::size_t PartLayout::index(std::size_t i) const {
  if (gap_ == 0) return i;
  const std::size_t b = i / len_;
  return i + gap_ * (b * threads_ + owner_of(i % len_, len_, threads_));
}

void set_threads(int requested) {
  const int threads = requested > 0 ? requested : omp_get_num_procs();
  omp_set_num_threads(threads);
  // Every thread of the team (the caller among them) in the simulation's floating-point mode: the caller first,
  // then a new thread team, whose workers inherit it. (No OpenMP region: its idle threads would spin beside the
  // team's for milliseconds.)
  flush_subnormals_to_zero();
  ThreadTeam::shared().resize(1, 1);
  try {
    ThreadTeam::shared().resize(static_cast<unsigned>(threads), processor_count());
  } catch (const std::system_error& e) {  // (the system's limit on threads, or on memory for their stacks)
    throw RuntimeError("--threads " + std::to_string(threads) + ": cannot start that many threads (" + e.what() + ")");
  }
}

}  // namespace frac
