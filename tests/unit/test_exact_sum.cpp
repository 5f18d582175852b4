// The exact sum: the correctly rounded sum of what was added, in any order, grouping and merge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/exact_sum.hpp"

namespace frac {
namespace {
__extension__ typedef __int128 int128;  // (GCC's and Clang's)

double exact_sum(const std::vector<double>& v) {
  ExactSum s;
  for (double x : v) s.add(x);
  return s.value();
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(ExactSum, EqualsTheRoundedSumOfIntegersOnAFixedGrid) {
  // Values k·2^-30, |k| < 2^53: their exact sum fits an __int128, whose conversion to double rounds to nearest.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> v;
    int128 sum = 0;
    const int count = 1 + static_cast<int>(rng() % 2000);
    for (int k = 0; k < count; ++k) {
      const auto m = static_cast<std::int64_t>(rng() >> 11) * ((rng() & 1) ? 1 : -1) >> (rng() % 40);
      v.push_back(std::ldexp(static_cast<double>(m), -30));
      sum += m;
    }
    EXPECT_TRUE(same_bits(exact_sum(v), std::ldexp(static_cast<double>(sum), -30))) << "trial " << trial;
  }
}

TEST(ExactSum, OrderGroupingAndMergeDoNotChangeABit) {
  // Magnitudes across the whole range, subnormals and both signs.
  std::mt19937_64 rng(11);
  std::vector<double> v;
  for (int k = 0; k < 20000; ++k) {
    const double m = std::uniform_real_distribution<double>(-1, 1)(rng);
    v.push_back(std::ldexp(m, static_cast<int>(rng() % 2100) - 1075));
  }
  const double reference = exact_sum(v);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(v.begin(), v.end(), rng);
    // In parts (threads), merged directly and through their settled words (processes).
    const std::size_t parts = 1 + rng() % 7;
    std::vector<ExactSum> part(parts);
    for (std::size_t k = 0; k < v.size(); ++k) part[rng() % parts].add(v[k]);
    ExactSum merged;
    std::array<std::int64_t, ExactSum::kWords> words{};
    for (const ExactSum& p : part) {
      merged.add(p);
      const auto w = p.words();
      for (std::size_t d = 0; d < ExactSum::kWords; ++d) words[d] += w[d];
    }
    EXPECT_TRUE(same_bits(merged.value(), reference));
    EXPECT_TRUE(same_bits(ExactSum::from_words(words).value(), reference));
  }
}

TEST(ExactSum, CancellationLeavesTheSmallTermsExact) {
  EXPECT_EQ(exact_sum({1e300, 1.0, -1e300}), 1.0);
  EXPECT_EQ(exact_sum({DBL_MAX, DBL_TRUE_MIN, -DBL_MAX}), DBL_TRUE_MIN);
  EXPECT_EQ(exact_sum({0.1, 0.2, -0.1, -0.2}), 0.0);
  EXPECT_EQ(exact_sum({-1.5, 0.25}), -1.25);
  EXPECT_TRUE(same_bits(exact_sum({}), 0.0));
  EXPECT_TRUE(same_bits(exact_sum({-0.0}), 0.0));  // an exact zero is +0
}

TEST(ExactSum, RoundsToNearestTiesToEven) {
  const double two53 = 9007199254740992.0;
  EXPECT_EQ(exact_sum({two53, 1.0}), two53);                    // a tie: to the even neighbour below
  EXPECT_EQ(exact_sum({two53, 3.0}), two53 + 4);                // a tie: to the even neighbour above
  EXPECT_EQ(exact_sum({two53, 1.0, DBL_TRUE_MIN}), two53 + 2);  // just above the tie
  EXPECT_EQ(exact_sum({-two53, -1.0, -DBL_TRUE_MIN}), -two53 - 2);
  EXPECT_EQ(exact_sum({1.0, 0x1p-53}), 1.0);
  EXPECT_EQ(exact_sum({1.0, 0x1p-53, 0x1p-105}), 1.0 + 0x1p-52);
  EXPECT_EQ(exact_sum({DBL_MIN, -DBL_TRUE_MIN}), DBL_MIN - DBL_TRUE_MIN);  // into the subnormals, exact
}

TEST(ExactSum, OverflowAndSpecialValues) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exact_sum({DBL_MAX, DBL_MAX}), inf);
  EXPECT_EQ(exact_sum({-DBL_MAX, -DBL_MAX}), -inf);
  EXPECT_EQ(exact_sum({DBL_MAX, DBL_MAX, -DBL_MAX}), DBL_MAX);  // the intermediate overflow is not kept
  EXPECT_EQ(exact_sum({1.0, inf}), inf);
  EXPECT_EQ(exact_sum({1.0, -inf}), -inf);
  EXPECT_TRUE(std::isnan(exact_sum({inf, -inf})));
  EXPECT_TRUE(std::isnan(exact_sum({1.0, std::nan("")})));
}

TEST(ExactSum, ManyLargeTermsCarryThroughMerges) {
  // 1000 parts of 1000 terms just below the largest double: every digit carries.
  ExactSum total;
  for (int p = 0; p < 1000; ++p) {
    ExactSum part;
    for (int k = 0; k < 1000; ++k) part.add(0x1p1000);
    total.add(part);
  }
  ExactSum back = total;
  for (int k = 0; k < 1000000 - 1; ++k) back.add(-0x1p1000);
  EXPECT_EQ(back.value(), 0x1p1000);
  EXPECT_EQ(total.value(), 1e6 * 0x1p1000);
}

}  // namespace
}  // namespace frac
