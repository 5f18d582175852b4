#pragma once
// A step of an engine as a list of named phases (predict, contact search, beams, contact laws, correct, break
// ...), run in order by one team of threads. A parallel phase is a loop over items of which every thread of the
// team runs its part (the phase's body splits them: static_range, or the blocks an earlier phase dealt out),
// with no barrier and no one-thread section inside it; a serial phase is run by one thread. Between two phases,
// and only there, the team waits for all its threads (the runner's barrier): a phase reads what the phases
// before it wrote. A phase may be conditional (`when`: the neighbour list when it is due), asked by every
// thread after the barrier before it: it must give every thread the same answer, so it reads only what no phase
// changes before the barrier that ends the phase it guards (the guarded phase included). The runner times every
// phase on the first thread's clock, its wait at the barrier included, so that a run can say where its time goes.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace frac {

struct Phase {
  std::string name;
  bool serial = false;
  // body(thread, threads): this thread's part of the phase's items in a team of `threads` (a serial phase runs
  // body(0, threads) on one thread of the team).
  std::function<void(std::size_t, std::size_t)> body;
  std::function<bool()> when;  // null: every time
};

// How long each phase took, summed over the runs of a list.
struct PhaseTime {
  std::string name;
  bool serial = false;
  std::int64_t calls = 0;
  double seconds = 0;
};

class Phases {
 public:
  Phases() = default;
  explicit Phases(std::vector<Phase> phases);
  void add(Phase phase);
  void add(const Phases& more);  // appends another list's phases
  std::size_t size() const { return phases_.size(); }
  const std::vector<Phase>& phases() const { return phases_; }

  // Runs the phases in order on a team of `threads` threads (1: the calling thread alone). Inside a parallel
  // region (a caller's team function), each thread of that team runs them in turn with the runner's barriers:
  // every thread of the region must call it.
  void run(std::size_t threads);

  const std::vector<PhaseTime>& times() const { return times_; }
  void clear_times();

 private:
  void run_on_team(std::size_t thread, std::size_t threads);
  std::vector<Phase> phases_;
  std::vector<PhaseTime> times_;
};

// The team a list of phases runs on: max_threads() threads when the work is `worth` it, else one.
std::size_t team_size(bool worth);

// The phases' times of several lists merged by name (in order of first appearance), for a report.
std::vector<PhaseTime> merged_times(const std::vector<const Phases*>& lists);

// A table of phase times: name, kind, calls, seconds, share of the total and µs per call; and the share spent in
// serial phases, one line each, after a first line naming `what` ("dem-run: phases of 5000 steps").
void write_phase_table(std::ostream& out, const std::string& what, const std::vector<PhaseTime>& times);

}  // namespace frac
