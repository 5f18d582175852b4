#pragma once
// A fixed pool of worker threads for the force loops, on a thread team of its own (core/thread_team.hpp: workers
// that spin, then sleep, between runs). run() hands the same job to every worker (the caller is worker 0) and
// returns when all are done; a job is a plain function pointer and a context pointer, so handing it over
// allocates nothing. Work is split by the job itself (contiguous ranges of nodes): every node's result is
// computed by the same instructions whichever thread runs it, so the number of threads never changes a bit of
// the result.
#include <cstddef>
#include <utility>

#include "core/thread_team.hpp"

namespace frac::rubber {

class ThreadPool {
 public:
  using Job = void (*)(void* context, int worker, int workers);

  // threads <= 0: one per processor.
  explicit ThreadPool(int threads = 1);
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(team_.size()); }
  void run(Job job, void* context);

  // [begin, end) of `n` items for `worker` of `workers`, in contiguous blocks.
  static std::pair<std::size_t, std::size_t> range(std::size_t n, int worker, int workers) {
    const auto w = static_cast<std::size_t>(worker), k = static_cast<std::size_t>(workers);
    return {n * w / k, n * (w + 1) / k};
  }

 private:
  ThreadTeam team_;
};

}  // namespace frac::rubber
