#include "core/parallel.hpp"

#include <omp.h>

namespace frac {

void set_threads(int requested) { omp_set_num_threads(requested > 0 ? requested : omp_get_num_procs()); }

}  // namespace frac
