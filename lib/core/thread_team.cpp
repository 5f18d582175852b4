#include "core/thread_team.hpp"

#include <algorithm>

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
    go_.advance();
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
  const std::uint32_t start = go_.now();
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
  go_.advance();  // (the job goes with it)
  member_run(0);
}

void ThreadTeam::work(unsigned index, std::uint32_t seen) {
  const std::uint32_t spins = spin::spins(threads_, cores_);
  for (;;) {
    seen = go_.wait_past(seen, spins);
    if (stop_) return;
    member_run(index);
  }
}

}  // namespace frac
