#pragma once
// A fixed pool of worker threads for the force loops. run() hands the same job to every worker (the
// caller is worker 0) and returns when all are done; a job is a plain function pointer and a context
// pointer, so handing it over allocates nothing. Work is split by the job itself (contiguous ranges
// of nodes): every node's result is computed by the same instructions whichever thread runs it, so
// the number of threads never changes a bit of the result.
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

namespace frac::rubber {

class ThreadPool {
 public:
  using Job = void (*)(void* context, int worker, int workers);

  // threads <= 0: one per hardware thread.
  explicit ThreadPool(int threads = 1);
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;
  ~ThreadPool();

  int size() const { return workers_; }
  void run(Job job, void* context);

  // [begin, end) of `n` items for `worker` of `workers`, in contiguous blocks.
  static std::pair<std::size_t, std::size_t> range(std::size_t n, int worker, int workers) {
    const auto w = static_cast<std::size_t>(worker), k = static_cast<std::size_t>(workers);
    return {n * w / k, n * (w + 1) / k};
  }

 private:
  void loop(int worker);
  int workers_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  Job job_ = nullptr;
  void* context_ = nullptr;
  unsigned long generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

}  // namespace frac::rubber
