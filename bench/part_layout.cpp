// What the layout of the per-coordinate arrays costs a team of threads: the loops of a Gear step over the DEM's
// coordinates (3 blocks, x, y and φ of every cell; each thread its part of every block, as the model's per-cell
// loops split the cells), timed on one thread and on the team for three layouts of the arrays:
//   contiguous : every array holds its 3n coordinates in order, so the threads' parts meet at five places;
//   r1..r5 apart (what dem-run does): the integrator's higher derivatives laid out with the threads' parts 2 KB
//                apart (core/parallel.hpp, PartLayout), q, v, a and the force contiguous, as the model reads them;
//   all apart  : every array in PartLayout.
// The loops are gear5's own (dynamics/integrator.hpp) and the accelerations a = f/m, on small values;
// nanoseconds per coordinate and step, per thread (median of ROUNDS rounds of STEPS steps). What it shows: two
// cores writing within about a kilobyte of each other's part slow each other's streams.
// Usage: part-layout [CELLS] [STEPS] [ROUNDS]   (1100, 20000, 5: the paper-scale explosion's disc)
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/parallel.hpp"
#include "dynamics/integrator.hpp"

namespace {

constexpr std::size_t kBlocks = 3;

// The eight arrays of one Gear step (r0 = q, r1..r5, v, a) and the force and 1/m of the model.
enum Array : std::size_t { r0, r1, r2, r3, r4, r5, v, a, force, inv_mass, kArrays };

struct Layout {
  const char* name;
  unsigned apart;  // bit k: array k in the PartLayout of the team
};

struct Arrays {
  std::array<std::vector<double>, kArrays> data;
  explicit Arrays(std::size_t size) {
    for (auto& d : data) d.assign(size, 1e-9);
  }
};

// One step's loops on this thread's parts: gear5's predictor (dynamics/integrator.hpp), barrier, accelerations,
// barrier, corrector, barrier. p(k, s): array k, shifted by s (the PartLayout shift of the part) if it is apart.
void step(Arrays& arr, const frac::PartLayout& layout, unsigned apart) {
  constexpr double dt = 1e-6;
  auto p = [&](Array k, std::size_t s) { return arr.data[k].data() + ((apart >> k) & 1u ? s : 0); };
  layout.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t s) {
    frac::dynamics::gear5_predict(first, last, p(r0, s), p(r1, s), p(r2, s), p(r3, s), p(r4, s), p(r5, s), p(v, s),
                                  1 / dt);
  });
  frac::team_barrier();
  layout.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t s) {
    double* acc = p(a, s);
    const double *f = p(force, s), *w = p(inv_mass, s);
#pragma omp simd
    for (std::size_t i = first; i < last; ++i) acc[i] = f[i] * w[i];
  });
  frac::team_barrier();
  layout.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t s) {
    frac::dynamics::gear5_correct(first, last, p(r0, s), p(r1, s), p(r2, s), p(r3, s), p(r4, s), p(r5, s), p(v, s),
                                  p(a, s), 0.5 * dt * dt, 1 / dt);
  });
  frac::team_barrier();
}

// Nanoseconds per coordinate and step of each thread (its loops and barriers), median over the rounds.
std::vector<double> measure(std::size_t cells, int threads, const Layout& layout, long steps, int rounds) {
  frac::set_threads(threads);
  const frac::PartLayout parts(kBlocks * cells, kBlocks, static_cast<std::size_t>(threads));
  Arrays arr(parts.size());
  std::vector<std::vector<double>> per_round(static_cast<std::size_t>(threads));
  for (int r = 0; r < rounds; ++r) {
    std::vector<double> ns(static_cast<std::size_t>(threads));
    frac::as_team(threads > 1, [&] {
      const auto t0 = std::chrono::steady_clock::now();
      for (long k = 0; k < steps; ++k) step(arr, parts, layout.apart);
      const std::chrono::duration<double, std::nano> t = std::chrono::steady_clock::now() - t0;
      ns[static_cast<std::size_t>(frac::thread_index())] = t.count();
    });
    const double coordinates = static_cast<double>(kBlocks * cells) / threads;
    for (std::size_t t = 0; t < ns.size(); ++t)
      per_round[t].push_back(ns[t] / static_cast<double>(steps) / coordinates);
  }
  for (const auto& d : arr.data) {
    const auto by_size = [](double x, double y) { return std::abs(x) < std::abs(y); };
    const double largest = *std::max_element(d.begin(), d.end(), by_size);
    if (!(std::abs(largest) < 1.0)) std::fprintf(stderr, "part-layout: the values grew to %g\n", largest);
  }
  std::vector<double> median;
  for (auto& v : per_round) {
    std::sort(v.begin(), v.end());
    median.push_back(v[v.size() / 2]);
  }
  return median;
}

}  // namespace

int main(int argc, char** argv) {
  const long cells = argc > 1 ? std::atol(argv[1]) : 1100;
  const long steps = argc > 2 ? std::atol(argv[2]) : 20000;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 5;
  if (cells < 2 || steps < 1 || rounds < 1) {
    std::fprintf(stderr, "usage: part-layout [CELLS] [STEPS] [ROUNDS]\n");
    return 2;
  }
  const unsigned r1_to_r5 = (1u << r1) | (1u << r2) | (1u << r3) | (1u << r4) | (1u << r5);
  const std::array<Layout, 3> layouts{
      {{"contiguous", 0u}, {"r1..r5 apart (dem-run)", r1_to_r5}, {"all apart", (1u << kArrays) - 1}}};
  const auto n = static_cast<std::size_t>(cells);
  std::printf("| layout | threads | ns per coordinate-step, per thread |\n|---|---|---|\n");
  const double one = measure(n, 1, layouts[0], steps, rounds)[0];
  std::printf("| contiguous | 1 | %.2f |\n", one);
  for (const Layout& layout : layouts) {
    const auto per_thread = measure(n, 2, layout, steps, rounds);
    std::printf("| %s | 2 | %.2f / %.2f |\n", layout.name, per_thread[0], per_thread[1]);
  }
  return 0;
}
