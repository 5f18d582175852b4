#pragma once
// Threading of the force loops, on OpenMP: a loop runs in parallel only above this many items, below it the
// fork and join cost more than the work. Each item writes its own slot; sums over items
// are done afterwards in item order, so results do not depend on the thread count.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace frac {

inline constexpr std::size_t kMinParallelItems = 256;

// The per-coordinate loops of a step (the integrator's, the force reset and the accelerations, the
// finiteness checks) are light: threads pay off from about a thousand coordinates.
inline constexpr std::size_t kMinParallelCoordinates = 4 * kMinParallelItems;

// The thread queries, for code that splits work by hand. max_threads: the size of the teams as_team makes.
int max_threads();
int thread_count();  // threads of the enclosing parallel region; 1 outside one (or in a serial section)
int thread_index();  // this thread's number in it
bool in_parallel();  // inside an active parallel region (one with more than one thread), not in a serial section
unsigned processor_count();  // processors this process may run on

// While one lives, this thread runs alone, as outside any region, though its team waits for it (a serial phase of
// core/phases): the queries above answer 1, 0 and false, team functions do all the work on it, and team_barrier
// and as_team wait for no other thread.
class SerialSection {
 public:
  SerialSection();
  ~SerialSection();
  SerialSection(const SerialSection&) = delete;
  SerialSection& operator=(const SerialSection&) = delete;
};
bool in_serial_section();

// Sets the number of threads of the force loops' teams: `requested`, or every core for 0; and puts each of them,
// and the caller, in the simulation's floating-point mode (core/float_mode.hpp: subnormals flushed to zero).
void set_threads(int requested);

// Thread t's part [first, last) of `items` under a static schedule of nt threads, as OpenMP's
// schedule(static) deals them out in GCC's libgomp: contiguous parts, the first items % nt one item longer.
struct Range {
  std::size_t first, last;
};
inline Range static_range(std::size_t items, std::size_t t, std::size_t nt) {
  const std::size_t q = items / nt, longer = items % nt;
  const std::size_t first = t < longer ? t * (q + 1) : longer * (q + 1) + (t - longer) * q;
  return {first, first + (t < longer ? q + 1 : q)};
}

// The thread whose part (static_range) of `items` holds `item`.
inline std::size_t owner_of(std::size_t item, std::size_t items, std::size_t nt) {
  const std::size_t q = items / nt, longer = items % nt;
  return item < longer * (q + 1) ? item / (q + 1) : longer + (item - longer * (q + 1)) / q;
}

// This thread's part of `items` under the static schedule of the enclosing team (all of them outside one).
inline Range this_thread_range(std::size_t items) {
  return static_range(items, static_cast<std::size_t>(thread_index()), static_cast<std::size_t>(thread_count()));
}

// Team functions. The loops of one DEM force evaluation share one parallel region: each is a team function, run
// by every thread of the region it is called from, each thread taking its part (static_range), with barriers
// (team_barrier) only where a thread reads what another wrote, and serial parts on the first thread (followed by
// a barrier when the others read what it wrote). Called outside any region, a team function runs every part on
// the calling thread. (Never call one from a part only some threads run: the others would not reach its
// barriers.)
// as_team runs `body` on every thread of a parallel region: the region it is called from, or a new one when
// `worth` it (above the sizes where threads pay off), so that a caller outside need not know. (Not worth it, or
// one thread: the caller alone.) `body` must not throw (an exception out of a parallel region ends the program).
template <class Body>
void as_team(bool worth, Body&& body) {
  if (in_parallel() || in_serial_section() || !worth || max_threads() == 1) {
    body();
    return;
  }
#pragma omp parallel
  body();
}

// Inside a team function: returns when every thread of the region has called it, what each wrote before visible
// to all after; nothing to wait for outside a region (or in a serial section).
inline void team_barrier() {
  if (in_serial_section()) return;
#pragma omp barrier
}

// One value per thread of a team, each on its own cache line: each thread writes its own, and after a
// barrier any thread reads them all, in thread order (a reduction without a region of its own).
template <class T>
class TeamSlots {
 public:
  // Outside the team (allocates when the thread count grows).
  void reserve(std::size_t threads) {
    if (slot_.size() < threads) slot_.resize(threads);
  }
  T& mine() { return slot_[static_cast<std::size_t>(thread_index())].value; }
  const T& operator[](std::size_t t) const { return slot_[t].value; }
  T& operator[](std::size_t t) { return slot_[t].value; }

 private:
  struct alignas(64) Slot {
    T value{};
  };
  std::vector<Slot> slot_;
};

// The per-coordinate loops over n = blocks·len coordinates laid out in `blocks` equal blocks (the DEM: x of
// every cell, then y, then φ) split them so that thread t takes the same part of every block,
// static_range(len, t, nt): the cells the per-cell loops of the forces (schedule(static)) give it, so each
// thread reads the values it wrote, in its own cache, instead of the other thread's. Element by element
// work gives the same bits whatever the split. (blocks = 0, or n not a multiple of it: one block.)
// coordinate_ranges: range(first, last) on thread t's part of every block in a team of nt; this_thread_...: this
// thread's part in the enclosing region.
template <class Body>
void coordinate_ranges(std::size_t n, std::size_t blocks, std::size_t t, std::size_t nt, Body&& range) {
  if (blocks == 0 || n % blocks != 0) blocks = 1;
  const std::size_t len = n / blocks;
  const Range r = static_range(len, t, nt);
  for (std::size_t b = 0; b < blocks; ++b) range(b * len + r.first, b * len + r.last);
}
template <class Body>
void this_thread_coordinate_ranges(std::size_t n, std::size_t blocks, Body&& range) {
  coordinate_ranges(n, blocks, static_cast<std::size_t>(thread_index()), static_cast<std::size_t>(thread_count()),
                    range);
}

// An array only per-coordinate loops touch (gear5's higher derivatives) laid out with the threads' parts apart.
// Two cores writing within a kilobyte of each other, either side of a split, each pull the other's lines with
// their prefetchers: the loops then run 2-4 times slower than on arrays kept apart (build/bench/part-layout
// measures it). The layout keeps the coordinates in order and shifts the part of thread t of
// block b (this_thread_coordinate_ranges' split for a team of `threads`) by kPartGap·(b·threads + t) entries; a
// team of one needs no gap.
class PartLayout {
 public:
  static constexpr std::size_t kPartGap = 256;  // doubles: 2 KB
  PartLayout() = default;
  PartLayout(std::size_t n, std::size_t blocks, std::size_t threads);
  std::size_t threads() const { return threads_; }
  std::size_t size() const { return n_ + gap_ * (blocks_ * threads_ - 1); }  // entries to allocate
  // Where coordinate i lives.
  std::size_t index(std::size_t i) const;
  // Inside a parallel region: range(first, last, shift) on the parts of this thread (of the layout's threads t
  // with t ≡ thread_index() modulo the team size: its own, in a team of `threads`), coordinate i of [first,
  // last) at entry shift + i. Outside one: on every part.
  template <class Body>
  void this_thread_parts(Body&& range) const {
    if (gap_ == 0 && thread_count() == 1) {
      range(std::size_t{0}, n_, std::size_t{0});
      return;
    }
    const auto team = static_cast<std::size_t>(thread_count());
    for (auto t = static_cast<std::size_t>(thread_index()); t < threads_; t += team) {
      const Range r = static_range(len_, t, threads_);
      for (std::size_t b = 0; b < blocks_; ++b) range(b * len_ + r.first, b * len_ + r.last, gap_ * (b * threads_ + t));
    }
  }

 private:
  std::size_t n_ = 0, blocks_ = 1, len_ = 0, threads_ = 1, gap_ = 0;
};

// A per-coordinate loop: range(first, last) on contiguous ranges that cover [0, n) once, split among the
// threads as above when n is above kMinParallelCoordinates, in one call otherwise.
template <class Body>
void for_coordinate_ranges(std::size_t n, std::size_t blocks, Body&& range) {
  if (n <= kMinParallelCoordinates || in_parallel()) {  // (inside a team: all on the calling thread)
    range(std::size_t{0}, n);
    return;
  }
  as_team(true, [&] { this_thread_coordinate_ranges(n, blocks, range); });
}

// The same loop with a sum: range(first, last) returns a double, and the results are added. The order of
// the additions depends on the thread count: only for sums that are exact in any order (Σ x·0, which is 0
// or NaN: the finiteness checks).
template <class Body>
double sum_over_coordinate_ranges(std::size_t n, std::size_t blocks, Body&& range) {
  constexpr std::size_t kMostThreads = 64;  // (a team's partial sums on the stack; more threads: one does it all)
  if (n <= kMinParallelCoordinates || in_parallel() || static_cast<std::size_t>(max_threads()) > kMostThreads)
    return range(std::size_t{0}, n);
  struct alignas(64) Part {
    double sum = 0;
  };
  Part part[kMostThreads];
  std::size_t threads = 1;
  as_team(true, [&] {
    double sum = 0;
    this_thread_coordinate_ranges(n, blocks, [&](std::size_t first, std::size_t last) { sum += range(first, last); });
    const auto t = static_cast<std::size_t>(thread_index());
    part[t].sum = sum;
    if (t == 0) threads = static_cast<std::size_t>(thread_count());
  });
  double sum = 0;
  for (std::size_t t = 0; t < threads; ++t) sum += part[t].sum;
  return sum;
}

}  // namespace frac
