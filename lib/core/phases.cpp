#include "core/phases.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <ostream>

#include "core/parallel.hpp"

namespace frac {

Phases::Phases(std::vector<Phase> phases) {
  for (Phase& p : phases) add(std::move(p));
}

void Phases::add(Phase phase) {
  times_.push_back({phase.name, phase.serial, 0, 0.0});
  phases_.push_back(std::move(phase));
}

void Phases::add(const Phases& more) {
  for (const Phase& p : more.phases_) add(p);
}

void Phases::clear_times() {
  for (PhaseTime& t : times_) t.calls = 0, t.seconds = 0;
}

std::size_t team_size(bool worth) { return worth ? static_cast<std::size_t>(max_threads()) : 1; }

void Phases::run(std::size_t threads) {
  if (in_parallel()) {
    run_on_team(static_cast<std::size_t>(thread_index()), static_cast<std::size_t>(thread_count()));
  } else if (threads > 1 && !in_serial_section()) {
    const int team = static_cast<int>(threads);
#pragma omp parallel num_threads(team)
    run_on_team(static_cast<std::size_t>(omp_get_thread_num()), static_cast<std::size_t>(omp_get_num_threads()));
  } else {
    run_on_team(0, 1);
  }
}

void Phases::run_on_team(std::size_t thread, std::size_t threads) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point last = thread == 0 ? Clock::now() : Clock::time_point{};
  for (std::size_t k = 0; k < phases_.size(); ++k) {
    const Phase& p = phases_[k];
    if (p.when && !p.when()) continue;
    if (!p.serial) {
      p.body(thread, threads);
    } else if (thread == 0) {
      const SerialSection alone;  // (what it calls does all its work on this thread)
      p.body(0, threads);
    }
    if (threads > 1) {
#pragma omp barrier
    }
    if (thread == 0) {
      const Clock::time_point now = Clock::now();
      times_[k].seconds += std::chrono::duration<double>(now - last).count();
      ++times_[k].calls;
      last = now;
    }
  }
}

std::vector<PhaseTime> merged_times(const std::vector<const Phases*>& lists) {
  std::vector<PhaseTime> out;
  for (const Phases* list : lists) {
    for (const PhaseTime& t : list->times()) {
      auto it = out.begin();
      while (it != out.end() && it->name != t.name) ++it;
      if (it == out.end()) {
        out.push_back(t);
      } else {
        it->calls += t.calls;
        it->seconds += t.seconds;
      }
    }
  }
  return out;
}

void write_phase_table(std::ostream& out, const std::string& what, const std::vector<PhaseTime>& times) {
  double total = 0, serial = 0;
  for (const PhaseTime& t : times) {
    total += t.seconds;
    if (t.serial) serial += t.seconds;
  }
  char line[160];
  out << what << "\n";
  std::snprintf(line, sizeof line, "  %-34s %-8s %10s %10s %7s %10s\n", "phase", "kind", "calls", "seconds", "share",
                "us/call");
  out << line;
  for (const PhaseTime& t : times) {
    if (t.calls == 0) continue;
    std::snprintf(line, sizeof line, "  %-34s %-8s %10lld %10.4f %6.2f%% %10.2f\n", t.name.c_str(),
                  t.serial ? "serial" : "parallel", static_cast<long long>(t.calls), t.seconds,
                  total > 0 ? 100 * t.seconds / total : 0.0, 1e6 * t.seconds / static_cast<double>(t.calls));
    out << line;
  }
  std::snprintf(line, sizeof line, "  total %.4f s, serial phases %.2f%%\n", total,
                total > 0 ? 100 * serial / total : 0.0);
  out << line;
}

}  // namespace frac
