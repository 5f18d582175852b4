#include "rubber/thread_pool.hpp"

#include "core/parallel.hpp"

namespace frac::rubber {

ThreadPool::ThreadPool(int threads) {
  const unsigned cores = processor_count();
  team_.resize(threads <= 0 ? cores : static_cast<unsigned>(threads), cores);
}

void ThreadPool::run(Job job, void* context) {
  struct Call {
    Job job;
    void* context;
  } call{job, context};
  team_.run(
      [](void* p) {
        const auto& c = *static_cast<const Call*>(p);
        const TeamMember& me = team_member();
        c.job(c.context, static_cast<int>(me.index), static_cast<int>(me.count));
      },
      &call);
}

}  // namespace frac::rubber
