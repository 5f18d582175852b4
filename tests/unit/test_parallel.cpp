// The split of the per-coordinate loops among threads (core/parallel.hpp) and the finiteness check that
// uses it (core/finite.hpp).
#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <vector>

#include "core/finite.hpp"
#include "core/float_mode.hpp"
#include "core/parallel.hpp"
#include "test_support.hpp"

namespace {

// static_range deals out what OpenMP's schedule(static) deals out (and owner_of inverts it): the per-cell force
// loops and the per-coordinate loops must give a thread the same cells.
// After set_threads, every thread of the team flushes subnormal results and operands to zero (the simulation's
// floating-point mode, core/float_mode.hpp), and normal numbers are untouched.
TEST(Parallel, ThreadsFlushSubnormalsToZero) {
  for (const int threads : {1, 2, 3}) {
    const frac::test::ThreadCount thread_count(threads);
    std::vector<double> product(static_cast<std::size_t>(threads), -1), sum(product), normal(product);
    volatile double tiny = 1e-300, scale = 1e-10, subnormal = 4.9e-324, one = 1.0;  // (not folded at compile time)
    frac::as_team(true, [&] {  // (on the thread team: each of its threads)
      const auto t = static_cast<std::size_t>(frac::thread_index());
      product[t] = tiny * scale;       // 1e-310: a subnormal result
      sum[t] = subnormal + subnormal;  // subnormal operands
      normal[t] = tiny * one;
    });
    if (!frac::flush_subnormals_to_zero()) GTEST_SKIP() << "no flush-to-zero mode on this target";
    // (Compared as bit patterns: in this mode a comparison reads a subnormal operand as zero.)
    for (std::size_t t = 0; t < static_cast<std::size_t>(threads); ++t) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(product[t]), 0u) << threads << " threads, thread " << t;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(sum[t]), 0u) << threads << " threads, thread " << t;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(normal[t]), std::bit_cast<std::uint64_t>(1e-300)) << t;
    }
  }
}

TEST(Parallel, StaticRangeMatchesOpenMPStaticSchedule) {
  for (const int threads : {1, 2, 3, 4}) {
    for (const std::size_t items : {0u, 1u, 2u, 5u, 7u, 1100u, 1103u}) {
      std::vector<int> owner(items, -1);
#pragma omp parallel for schedule(static) num_threads(threads)
      for (std::size_t k = 0; k < items; ++k) owner[k] = frac::thread_index();
      for (std::size_t t = 0; t < static_cast<std::size_t>(threads); ++t) {
        const frac::Range r = frac::static_range(items, t, static_cast<std::size_t>(threads));
        for (std::size_t k = 0; k < items; ++k)
          EXPECT_EQ(owner[k] == static_cast<int>(t), k >= r.first && k < r.last)
              << items << " items, " << threads << " threads, item " << k << ", thread " << t;
      }
      for (std::size_t k = 0; k < items; ++k) {
        EXPECT_EQ(frac::owner_of(k, items, static_cast<std::size_t>(threads)), static_cast<std::size_t>(owner[k]))
            << items << " items, " << threads << " threads, item " << k;
      }
    }
  }
}

// Every coordinate is visited once, and on two threads each thread takes the same cells in every block.
TEST(Parallel, CoordinateRangesCoverEveryCoordinateOnceAlignedWithTheCells) {
  for (const int threads : {1, 2, 3}) {
    const frac::test::ThreadCount thread_count(threads);
    for (const std::size_t cells : {5u, 1100u, 1103u, 4000u}) {
      for (const std::size_t blocks : {1u, 3u}) {
        const std::size_t n = cells * blocks;
        std::vector<int> visits(n, 0), owner(n, -1);
        frac::for_coordinate_ranges(n, blocks, [&](std::size_t first, std::size_t last) {
          for (std::size_t i = first; i < last; ++i) {
            ++visits[i];
            owner[i] = frac::thread_index();
          }
        });
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(visits[i], 1) << n << " coordinates, index " << i;
        if (n <= frac::kMinParallelCoordinates) continue;  // one call on the calling thread
        for (std::size_t b = 1; b < blocks; ++b)
          for (std::size_t c = 0; c < cells; ++c) EXPECT_EQ(owner[b * cells + c], owner[c]) << "cell " << c;
      }
    }
  }
}

// PartLayout: every coordinate is visited once, at the entry index() gives, distinct entries inside size(); in a
// team of the layout's size each thread takes the cells the per-coordinate loops give it, and entries of
// different threads' parts lie at least kPartGap apart; a team of another size still visits each once.
TEST(Parallel, PartLayoutKeepsTheThreadsPartsApart) {
  for (const std::size_t layout_threads : {1u, 2u, 3u}) {
    for (const std::size_t cells : {1u, 2u, 5u, 1100u, 1103u}) {
      for (const std::size_t blocks : {1u, 3u}) {
        const std::size_t n = cells * blocks;
        const frac::PartLayout layout(n, blocks, layout_threads);
        for (const int team : {1, 2, 3}) {
          std::vector<int> visits(n, 0), owner(n, -1);
          std::vector<std::size_t> entry(n, 0);
#pragma omp parallel num_threads(team)
          layout.this_thread_parts([&](std::size_t first, std::size_t last, std::size_t shift) {
            for (std::size_t i = first; i < last; ++i) {
              ++visits[i];
              owner[i] = frac::thread_index();
              entry[i] = shift + i;
            }
          });
          std::vector<char> used(layout.size(), 0);
          for (std::size_t i = 0; i < n; ++i) {
            ASSERT_EQ(visits[i], 1) << n << " coordinates, team " << team << ", index " << i;
            ASSERT_EQ(entry[i], layout.index(i)) << "index " << i;
            ASSERT_LT(entry[i], layout.size());
            ASSERT_FALSE(used[entry[i]]) << "entry " << entry[i] << " twice";
            used[entry[i]] = 1;
          }
          if (static_cast<std::size_t>(team) != layout_threads) continue;
          for (std::size_t i = 0; i < n; ++i) {
            const frac::Range r = frac::static_range(cells, static_cast<std::size_t>(owner[i]), layout_threads);
            EXPECT_TRUE(i % cells >= r.first && i % cells < r.last) << "coordinate " << i << ", thread " << owner[i];
            if (i + 1 < n && owner[i + 1] != owner[i]) {
              EXPECT_GE(entry[i + 1] - entry[i], frac::PartLayout::kPartGap) << "coordinates " << i << ", " << i + 1;
            }
          }
        }
      }
    }
  }
}

// A single NaN or infinity anywhere, in any block, on any thread count, is found.
TEST(Parallel, AllFiniteFindsAnyNonFiniteValue) {
  for (const int threads : {1, 2}) {
    const frac::test::ThreadCount thread_count(threads);
    for (const std::size_t n : {7u, 3300u, 3309u}) {
      std::vector<double> x(n, 1e300), y(n, -1e300);
      EXPECT_TRUE(frac::all_finite(x, 3)) << n;
      EXPECT_TRUE(frac::all_finite(x, y, 3)) << n;
      for (const std::size_t at : {std::size_t{0}, n / 3 - 1, n / 3, n / 2, n - 1}) {
        for (const double bad : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
          x[at] = bad;
          EXPECT_FALSE(frac::all_finite(x, 3)) << n << " values, " << bad << " at " << at;
          EXPECT_FALSE(frac::all_finite(x)) << n << " values, " << bad << " at " << at;
          EXPECT_FALSE(frac::all_finite(x, y, 3)) << n << " values, " << bad << " at " << at << " of the first";
          EXPECT_FALSE(frac::all_finite(y, x, 3)) << n << " values, " << bad << " at " << at << " of the second";
          x[at] = 1e300;
        }
      }
    }
  }
}

// The test in passing (non_finite_bit, OR-ed over a loop): only NaN and ±inf set the top bit, whatever the values
// OR-ed with them; the largest finite numbers, subnormals, zeros and negative numbers do not.
TEST(Parallel, NonFiniteBitMarksOnlyNaNAndInfinity) {
  using limits = std::numeric_limits<double>;
  const std::vector<double> finite{0.0,
                                   -0.0,
                                   1.0,
                                   -1.0,
                                   limits::max(),
                                   -limits::max(),
                                   limits::min(),
                                   limits::denorm_min(),
                                   -limits::denorm_min(),
                                   1e-310,
                                   0x1.fffffffffffffp1023};
  const std::vector<double> not_finite{limits::quiet_NaN(), -limits::quiet_NaN(), limits::signaling_NaN(),
                                       limits::infinity(), -limits::infinity()};
  std::uint64_t all = 0;
  for (const double x : finite) {
    EXPECT_FALSE(frac::non_finite_seen(frac::non_finite_bit(x))) << x;
    all |= frac::non_finite_bit(x);
  }
  EXPECT_FALSE(frac::non_finite_seen(all));
  for (const double x : not_finite) {
    EXPECT_TRUE(frac::non_finite_seen(frac::non_finite_bit(x))) << x;
    EXPECT_TRUE(frac::non_finite_seen(all | frac::non_finite_bit(x))) << x;
  }
}

// team_barrier in as_team's regions and in other OpenMP regions: after the k-th barrier every thread sees what
// every other wrote before it.
TEST(Parallel, TeamBarrierInAsTeamAndInOtherRegions) {
  for (const int threads : {2, 3}) {
    const frac::test::ThreadCount thread_count(threads);
    std::vector<int> value(static_cast<std::size_t>(threads), 0);
    int wrong = 0;
    auto body = [&] {
      const auto t = static_cast<std::size_t>(frac::thread_index());
      const auto nt = static_cast<std::size_t>(frac::thread_count());
      for (int k = 1; k <= 500; ++k) {
        value[t] = k;
        frac::team_barrier();
        int seen = 0;
        for (std::size_t u = 0; u < nt; ++u) seen += value[u] == k ? 1 : 0;
        frac::team_barrier();
        if (seen != static_cast<int>(nt)) {
#pragma omp atomic
          ++wrong;
        }
      }
    };
    frac::as_team(true, body);
    EXPECT_EQ(wrong, 0) << threads << " threads, as_team";
    wrong = 0;
#pragma omp parallel
    body();
    EXPECT_EQ(wrong, 0) << threads << " threads, an OpenMP region";
    frac::team_barrier();  // (outside any region: nothing to wait for)
  }
}

}  // namespace
