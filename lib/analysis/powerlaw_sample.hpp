#pragma once
// The sample every power-law estimator works on: sorted distinct values with their multiplicities,
// logarithms and suffix sums, so that the MLE for any lower cutoff costs O(1) and a KS distance walks
// distinct values only. Also the input checks (no NaN, no infinities, no zeros or negatives, enough
// values) shared by the tool and the tests: bad values are refused with counts, never dropped.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/rng.hpp"

namespace frac::analysis {

struct Sample {
  std::vector<double> value;       // distinct values, ascending (all > 0)
  std::vector<std::int64_t> cum;   // size K+1: cum[k] = number of points below value[k]; cum[K] = n
  std::vector<double> log_rel;     // ln(value[k] / value[0])
  std::vector<double> suffix_log;  // size K+1: sum of log_rel over the points >= value[k]; suffix_log[K] = 0
  double log_ref = 0;              // ln value[0]
  bool integer = false;            // every value is a whole number

  std::int64_t n() const { return cum.empty() ? 0 : cum.back(); }
  std::size_t distinct() const { return value.size(); }
  std::int64_t count(std::size_t k) const { return cum[k + 1] - cum[k]; }
  // Number of points >= value[k].
  std::int64_t tail(std::size_t k) const { return n() - cum[k]; }
  // Index of the first distinct value >= x (distinct() when none).
  std::size_t first_at_least(double x) const;
};

// Builds a sample from positive finite values (any order). Call validate_values first.
Sample make_sample(std::vector<double> x);
// Builds a sample from distinct ascending values and their counts (zero counts are skipped).
Sample make_sample(std::span<const double> distinct_values, std::span<const std::int64_t> counts);

// Non-parametric bootstrap resample: n() points drawn with replacement.
Sample resample(const Sample& s, Rng& rng);
// One point drawn uniformly (with multiplicity) among the points below value[j].
double draw_below(const Sample& s, std::size_t j, Rng& rng);

// Smallest input a fit accepts.
inline constexpr std::int64_t kMinValues = 10;
inline constexpr std::size_t kMinDistinct = 3;

// Refuses (InputError) values a power-law fit cannot take, saying what is wrong and how many values are
// affected: NaN, infinities, zeros, negatives, fewer than kMinValues values, all values equal, fewer than
// kMinDistinct distinct values. `what` names the input in the message ("values.txt", "/fragments/mass").
void validate_values(std::span<const double> x, const std::string& what);

// True when every value is a whole number (exactly representable, below 2^53).
bool all_integers(std::span<const double> x);

// A seeded generator for replicate `index` of random stream `stream`: independent of thread count and order.
Rng replicate_rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

}  // namespace frac::analysis
