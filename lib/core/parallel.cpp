#include "core/parallel.hpp"

#include <omp.h>

#include "core/float_mode.hpp"

namespace frac {

namespace {
thread_local int g_serial = 0;  // serial sections open on this thread
}  // namespace

SerialSection::SerialSection() { ++g_serial; }
SerialSection::~SerialSection() { --g_serial; }
bool in_serial_section() { return g_serial > 0; }

int max_threads() { return omp_get_max_threads(); }
int thread_count() { return g_serial ? 1 : omp_get_num_threads(); }
int thread_index() { return g_serial ? 0 : omp_get_thread_num(); }
bool in_parallel() { return g_serial == 0 && omp_in_parallel() != 0; }
unsigned processor_count() { return static_cast<unsigned>(omp_get_num_procs()); }

PartLayout::PartLayout(std::size_t n, std::size_t blocks, std::size_t threads)
    : n_(n), blocks_(blocks == 0 || n % blocks != 0 ? 1 : blocks), threads_(threads == 0 ? 1 : threads) {
  len_ = n_ / blocks_;
  gap_ = threads_ > 1 ? kPartGap : 0;
}

std::size_t PartLayout::index(std::size_t i) const {
  if (gap_ == 0) return i;
  const std::size_t b = i / len_;
  return i + gap_ * (b * threads_ + owner_of(i % len_, len_, threads_));
}

void set_threads(int requested) {
  const int threads = requested > 0 ? requested : omp_get_num_procs();
  omp_set_num_threads(threads);
  // Every thread of the regions (the caller among them) in the simulation's floating-point mode, set in each
  // (OpenMP keeps its threads from region to region).
  flush_subnormals_to_zero();
  if (threads > 1) {
#pragma omp parallel
    flush_subnormals_to_zero();
  }
}

}  // namespace frac
