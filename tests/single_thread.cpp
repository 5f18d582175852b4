// Test processes run the force loops on one OpenMP thread unless OMP_NUM_THREADS says otherwise: ctest -j
// runs test processes side by side, and OpenMP threads of two processes competing for the same cores
// wait on each other at every barrier (a hundredfold slowdown seen on two cores). Results do not depend
// on the thread count; the end-to-end test of that asks for its threads (dem-run --threads 2).
#include <omp.h>

#include <cstdlib>

namespace {
const bool kOneThread = [] {
  if (std::getenv("OMP_NUM_THREADS") == nullptr) omp_set_num_threads(1);
  return true;
}();
}  // namespace
