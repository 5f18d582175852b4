// Run by mpirun -n P: each rank adds its share of one fixed list of doubles (every P-th, from its rank); the
// exact sum over the ranks must equal, bit for bit, the list's exact sum on one process, and the integer sum and
// the maximum theirs. Exit 0 when every rank agrees, 1 otherwise.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "comm/world.hpp"

int main(int argc, char** argv) {
  const frac::comm::World& world = frac::comm::World::start(argc, argv);
  // Magnitudes across the range of doubles and both signs, from a fixed linear congruential sequence.
  std::vector<double> terms;
  std::uint64_t state = 12345;
  for (int k = 0; k < 100000; ++k) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double m = static_cast<double>(state >> 11) * 0x1p-53 - 0.5;
    terms.push_back(std::ldexp(m, static_cast<int>((state >> 3) % 600) - 300));
  }
  frac::ExactSum all, mine;
  std::int64_t count = 0;
  double largest = -1e308;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    all.add(terms[k]);
    if (static_cast<int>(k % static_cast<std::size_t>(world.size())) != world.rank()) continue;
    mine.add(terms[k]);
    ++count;
    largest = std::max(largest, terms[k]);
  }
  const double total = world.sum(mine).value(), expected = all.value();
  double expected_max = -1e308;
  for (double t : terms) expected_max = std::max(expected_max, t);
  const bool ok = std::bit_cast<std::uint64_t>(total) == std::bit_cast<std::uint64_t>(expected) &&
                  world.sum(count) == static_cast<std::int64_t>(terms.size()) && world.max(largest) == expected_max;
  if (!ok || world.rank() == 0)
    std::printf("rank %d of %d: exact sum %a, on one process %a: %s\n", world.rank(), world.size(), total, expected,
                ok ? "same" : "DIFFERENT");
  return ok ? 0 : 1;
}
