// The machine's limits that the benchmarks' figures are read against, per core: the memory bandwidth of the
// STREAM triad a[k] = b[k] + s·c[k] (24 bytes a point, arrays far larger than the caches; the best of several
// passes) and the peak of double-precision floating point (independent multiply-add chains: as the portable
// build's baseline code runs them, as its AVX2 kernels do, and as fused multiply-adds, the native build's).
// Usage: machine-limits [THREADS]   (default 1; prints key value lines)
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Best triad bandwidth over `passes` passes, bytes/s.
double triad_bandwidth(std::size_t n, int passes) {
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  double best = 0;
  for (int p = 0; p < passes; ++p) {
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < n; ++k) a[k] = b[k] + s * c[k];
    best = std::max(best, 24.0 * static_cast<double>(n) / seconds_since(t0));
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return best;
}

// Floating-point operations per second of 64 independent chains x = x·m + d per thread (2 flops each: enough
// chains to hide the latency), as `body` compiles them.
constexpr int kChains = 64;
template <class Body>
double flop_rate(long iterations, Body body) {
  double total = 0;
  const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel reduction(+ : total)
  {
    double x[kChains];
    for (int k = 0; k < kChains; ++k) x[k] = 1.0 + 1e-3 * k;
    body(x, iterations);
    for (int k = 0; k < kChains; ++k) total += x[k];
  }
  const double s = seconds_since(t0);
  volatile double sink = total;
  (void)sink;
  return 2.0 * kChains * static_cast<double>(iterations) * omp_get_max_threads() / s;
}

// The baseline x86-64 (SSE2: two doubles an instruction), AVX2 (four), and AVX2 with FMA (a multiply-add in one).
void chains_sse2(double* x, long iterations) {
  for (long it = 0; it < iterations; ++it)
#pragma omp simd
    for (int k = 0; k < kChains; ++k) x[k] = x[k] * 0.999999 + 1e-7;
}
__attribute__((target("avx2"))) void chains_avx2(double* x, long iterations) {
  for (long it = 0; it < iterations; ++it)
#pragma omp simd
    for (int k = 0; k < kChains; ++k) x[k] = x[k] * 0.999999 + 1e-7;
}
__attribute__((target("avx2,fma"))) void chains_fma(double* x, long iterations) {
  for (long it = 0; it < iterations; ++it)
#pragma omp simd
    for (int k = 0; k < kChains; ++k) x[k] = __builtin_fma(x[k], 0.999999, 1e-7);
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  omp_set_num_threads(std::max(1, threads));
  std::printf("threads %d\n", std::max(1, threads));
  std::printf("stream_triad_GB_per_s %.2f\n", triad_bandwidth(std::size_t{1} << 25, 10) / 1e9);
  std::printf("flops_sse2_GFLOP_per_s %.2f\n", flop_rate(50'000'000, chains_sse2) / 1e9);
  if (__builtin_cpu_supports("avx2"))
    std::printf("flops_avx2_GFLOP_per_s %.2f\n", flop_rate(50'000'000, chains_avx2) / 1e9);
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    std::printf("flops_avx2_fma_GFLOP_per_s %.2f\n", flop_rate(50'000'000, chains_fma) / 1e9);
}
