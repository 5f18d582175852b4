#pragma once
// The threads that run the force loops' teams (core/parallel.hpp: as_team): the caller and threads − 1 workers
// that wait for work by spinning, then sleeping. OpenMP's region in GCC's libgomp starts and ends with futex
// system calls (bench/team_barrier.cpp times both), and on a kernel that isolates page tables (PTI) without
// PCID every system call also empties the TLB, so the loops after it walk the page tables again. Here a region
// costs two spins on a shared counter while the workers are awake (they spin ~1 ms after a run, longer than the
// serial work between two force evaluations, then sleep on a futex).
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "core/spin_wait.hpp"
#include "core/team_barrier.hpp"

namespace frac {

class ThreadTeam {
 public:
  using Job = void (*)(void* context);
  ThreadTeam() = default;
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  ~ThreadTeam();
  // The process's team, shared by every team function.
  static ThreadTeam& shared();
  // The caller and threads − 1 workers, started now by the caller (they inherit its floating-point mode), on
  // `cores` processors (more threads than cores: they spin briefly before they sleep). Not while a job runs.
  void resize(unsigned threads, unsigned cores);
  unsigned size() const { return threads_; }
  // Runs job(context) on every thread of the team, the caller as thread 0, each with its index, the team's size
  // and barrier set (team_member), and returns when every one has returned. A job must not throw.
  void run(Job job, void* context);

 private:
  void work(unsigned index, std::uint32_t seen);
  void member_run(unsigned index);
  std::vector<std::thread> workers_;
  std::unique_ptr<TeamBarrier> barrier_;  // (inside the job, and the end of each run)
  alignas(64) spin::WaitCount go_;  // (moves on for each run, and to stop the workers)
  Job job_ = nullptr;
  void* context_ = nullptr;
  bool stop_ = false;
  unsigned threads_ = 1, cores_ = 1;
};

// Who this thread is in the team whose job it runs (all zero outside one).
struct TeamMember {
  unsigned index = 0, count = 0;
  TeamBarrier* barrier = nullptr;
};
TeamMember& team_member();

}  // namespace frac
