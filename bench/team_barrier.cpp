// What a barrier costs a team of threads: OpenMP's (GCC's libgomp) against the team barrier of the force loops
// (core/team_barrier.hpp), and a parallel region's start and end. Median of ROUNDS rounds, µs each.
// Usage: team-barrier [THREADS] [BARRIERS] [ROUNDS]   (2, 100000, 5)
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/parallel.hpp"
#include "core/team_barrier.hpp"

namespace {

template <class Fn>
double median_us(int rounds, long per_round, Fn&& fn) {
  std::vector<double> us;
  for (int r = 0; r < rounds; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    const auto t1 = std::chrono::steady_clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count() / static_cast<double>(per_round));
  }
  std::sort(us.begin(), us.end());
  return us[us.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const long barriers = argc > 2 ? std::atol(argv[2]) : 100000;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 5;
  if (threads < 1 || barriers < 1 || rounds < 1) {
    std::fprintf(stderr, "usage: team-barrier [THREADS] [BARRIERS] [ROUNDS]\n");
    return 2;
  }
  const double omp_barrier = median_us(rounds, barriers, [&] {
#pragma omp parallel num_threads(threads)
    for (long k = 0; k < barriers; ++k) {
#pragma omp barrier
    }
  });
  frac::TeamBarrier team(static_cast<unsigned>(threads), frac::processor_count());
  const double team_barrier = median_us(rounds, barriers, [&] {
#pragma omp parallel num_threads(threads)
    for (long k = 0; k < barriers; ++k) team.wait();
  });
  const long regions = barriers / 10;
  const double region = median_us(rounds, regions, [&] {
    for (long k = 0; k < regions; ++k) {
#pragma omp parallel num_threads(threads)
      team.wait();  // (something to do: an empty region may be left out)
    }
  });
  std::printf("| threads | OpenMP barrier, µs | team barrier, µs | ratio | parallel region with one team barrier, µs |\n");
  std::printf("|---|---|---|---|---|\n");
  std::printf("| %d | %.3f | %.3f | %.2f | %.3f |\n", threads, omp_barrier, team_barrier, team_barrier / omp_barrier,
              region);
  return 0;
}
