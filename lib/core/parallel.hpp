#pragma once
// Threading policy of the force loops (OpenMP): a loop runs in parallel only above this many items,
// below it the fork and join cost more than the work. Each item writes its own slot; sums over items
// are done afterwards in item order, so results do not depend on the thread count.
#include <cstddef>

namespace frac {

inline constexpr std::size_t kMinParallelItems = 256;

// OpenMP's thread queries, for code that splits work by hand.
int max_threads();
int thread_count();  // threads of the enclosing parallel region
int thread_index();  // this thread's number in it

// Sets the number of OpenMP threads of the force loops: `requested`, or every core for 0.
void set_threads(int requested);

}  // namespace frac
