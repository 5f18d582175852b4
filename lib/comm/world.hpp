#pragma once
// The processes of one run. Started on its own, a tool is one process and never starts MPI (MPI_Init alone costs
// 0.3-0.5 s, a third of a paper-scale explosion); started by a launcher (mpirun, srun --mpi=pmix) it is one rank
// of several. The force terms never see this layer: only the decomposition, the exchanges and the writers do.
// Every collective here is exact or order-free (integers, MIN, MAX, exact sums), so that a result does not
// depend on the number of ranks.
#include <cstdint>
#include <string>

#include "core/exact_sum.hpp"

namespace frac::comm {

class World {
 public:
  // The world of this process, MPI started (thread support: calls from the main thread only) when a launcher
  // started it (OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK in its environment); the first call starts it, later
  // calls return it. MPI ends at exit.
  static const World& start(int& argc, char**& argv);

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Collectives: every rank calls them, in the same order.
  ExactSum sum(const ExactSum& part) const;
  std::int64_t sum(std::int64_t part) const;
  double max(double part) const;

 private:
  World() = default;
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

// For a run that does not split over ranks yet: started as several, rank 0 refuses (a UsageError naming the
// count) and the other ranks end at once with the same exit code, so that the job prints one message.
void require_one_rank(const World& world);

}  // namespace frac::comm
