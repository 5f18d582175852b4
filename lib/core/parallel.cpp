#include "core/parallel.hpp"

#include <omp.h>

namespace frac {

int set_threads(int requested) {
  const int threads = requested > 0 ? requested : omp_get_num_procs();
  omp_set_num_threads(threads);
  return threads;
}

}  // namespace frac
