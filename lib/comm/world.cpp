#include "comm/world.hpp"

#define OMPI_SKIP_MPICXX 1  // (OpenMPI's deprecated C++ bindings: the C interface is all this layer uses)
#include <mpi.h>

#include <cstdlib>

#include "core/error.hpp"

namespace frac::comm {
namespace {
void finish() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw RuntimeError(std::string("MPI: ") + what + " failed");
}

bool launched_as_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}
}  // namespace

const World& World::start(int& argc, char**& argv) {
  static const World world = [&] {
    World w;
    if (!launched_as_rank()) return w;
    int provided = 0;
    check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    std::atexit(finish);
    w.mpi_ = true;
    check(MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &w.size_), "MPI_Comm_size");
    return w;
  }();
  return world;
}

ExactSum World::sum(const ExactSum& part) const {
  if (!mpi_) return part;
  auto words = part.words();
  check(MPI_Allreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD),
        "MPI_Allreduce (exact sum)");
  return ExactSum::from_words(words);
}

std::int64_t World::sum(std::int64_t part) const {
  if (mpi_) check(MPI_Allreduce(MPI_IN_PLACE, &part, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce (sum)");
  return part;
}

double World::max(double part) const {
  if (mpi_) check(MPI_Allreduce(MPI_IN_PLACE, &part, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce (max)");
  return part;
}

void require_one_rank(const World& world) {
  if (world.size() == 1) return;
  if (world.rank() != 0) std::exit(kExitBadInput);
  throw UsageError("started as " + std::to_string(world.size()) +
                   " ranks: this program runs one process per run (start it without mpirun or srun -n)");
}

}  // namespace frac::comm
