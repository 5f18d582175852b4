#include "core/thread_team.hpp"

#include <algorithm>

#include "core/spin_wait.hpp"

namespace frac {

TeamMember& team_member() {
  thread_local TeamMember member;
  return member;
}

ThreadTeam& ThreadTeam::shared() {
  static ThreadTeam team;
  return team;
}

ThreadTeam::~ThreadTeam() { resize(1, 1); }

void ThreadTeam::resize(unsigned threads, unsigned cores) {
  if (threads == 0) threads = 1;
  if (threads == threads_) return;
  if (!workers_.empty()) {
    stop_ = true;
    go_.fetch_add(1, std::memory_order_seq_cst);
    spin::wake_all(go_);
    for (std::thread& w : workers_) w.join();
    workers_.clear();
    stop_ = false;
  }
  threads_ = 1;
  barrier_.reset();
  if (threads == 1) return;
  threads_ = threads;
  cores_ = std::max(1u, cores);
  barrier_ = std::make_unique<TeamBarrier>(threads, cores_);
  // (The count each worker waits to change: the next run's, whenever the worker gets to look.)
  const std::uint32_t start = go_.load(std::memory_order_relaxed);
  workers_.reserve(threads - 1);
  for (unsigned k = 1; k < threads; ++k) workers_.emplace_back([this, k, start] { work(k, start); });
}

void ThreadTeam::member_run(unsigned index) {
  TeamMember& me = team_member();
  me = {index, threads_, barrier_.get()};
  job_(context_);
  me = {};
  barrier_->wait();  // (the end of the run: every member's work done and visible)
}

void ThreadTeam::run(Job job, void* context) {
  if (workers_.empty()) {
    TeamMember& me = team_member();
    me = {0, 1, nullptr};
    job(context);
    me = {};
    return;
  }
  job_ = job;
  context_ = context;
  // The job goes with the new count (seq_cst: a worker about to sleep either sees it or is counted and woken).
  go_.fetch_add(1, std::memory_order_seq_cst);
  if (sleepers_.load(std::memory_order_seq_cst) != 0) spin::wake_all(go_);
  member_run(0);
}

void ThreadTeam::work(unsigned index, std::uint32_t seen) {
  const std::uint32_t spins = spin::spins(threads_, cores_);
  for (;;) {
    std::uint32_t now = go_.load(std::memory_order_acquire);
    for (std::uint32_t s = 0; now == seen && s < spins; ++s) {
      spin::cpu_relax();
      now = go_.load(std::memory_order_acquire);
    }
    if (now == seen) {
      sleepers_.fetch_add(1, std::memory_order_seq_cst);
      while ((now = go_.load(std::memory_order_seq_cst)) == seen) spin::sleep_while(go_, seen);
      sleepers_.fetch_sub(1, std::memory_order_relaxed);
    }
    seen = now;
    if (stop_) return;
    member_run(index);
  }
}

}  // namespace frac
