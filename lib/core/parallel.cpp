#include "core/parallel.hpp"

#include <omp.h>

namespace frac {

int max_threads() { return omp_get_max_threads(); }
int thread_count() { return omp_get_num_threads(); }
int thread_index() { return omp_get_thread_num(); }

void set_threads(int requested) { omp_set_num_threads(requested > 0 ? requested : omp_get_num_procs()); }

}  // namespace frac
