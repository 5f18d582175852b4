#include "analysis/powerlaw_sample.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace frac::analysis {

std::size_t Sample::first_at_least(double x) const {
  return static_cast<std::size_t>(std::lower_bound(value.begin(), value.end(), x) - value.begin());
}

namespace {

void finish(Sample& s) {
  const std::size_t K = s.value.size();
  s.log_ref = K ? std::log(s.value[0]) : 0.0;
  s.log_rel.resize(K);
  for (std::size_t k = 0; k < K; ++k) s.log_rel[k] = std::log(s.value[k]) - s.log_ref;
  if (K) s.log_rel[0] = 0.0;
  s.suffix_log.assign(K + 1, 0.0);
  long double acc = 0;
  for (std::size_t k = K; k-- > 0;) {
    acc += static_cast<long double>(s.count(k)) * s.log_rel[k];
    s.suffix_log[k] = static_cast<double>(acc);
  }
  s.integer = all_integers(s.value);
}

}  // namespace

Sample make_sample(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  Sample s;
  s.cum.push_back(0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i == 0 || x[i] != x[i - 1]) {
      if (i) s.cum.push_back(static_cast<std::int64_t>(i));
      s.value.push_back(x[i]);
    }
  }
  if (!x.empty()) s.cum.push_back(static_cast<std::int64_t>(x.size()));
  finish(s);
  return s;
}

Sample make_sample(std::span<const double> distinct_values, std::span<const std::int64_t> counts) {
  Sample s;
  s.cum.push_back(0);
  for (std::size_t k = 0; k < distinct_values.size(); ++k) {
    if (counts[k] <= 0) continue;
    s.value.push_back(distinct_values[k]);
    s.cum.push_back(s.cum.back() + counts[k]);
  }
  finish(s);
  return s;
}

namespace {
// Uniform index in [0, n).
std::int64_t uniform_index(Rng& rng, std::int64_t n) {
  const auto r = static_cast<std::int64_t>(rng.uniform() * static_cast<double>(n));
  return std::min(r, n - 1);
}
// Distinct index of point number r (0-based, in sorted order).
std::size_t distinct_of_point(const Sample& s, std::int64_t r) {
  return static_cast<std::size_t>(std::upper_bound(s.cum.begin(), s.cum.end(), r) - s.cum.begin()) - 1;
}
}  // namespace

Sample resample(const Sample& s, Rng& rng) {
  std::vector<std::int64_t> counts(s.distinct(), 0);
  const std::int64_t n = s.n();
  for (std::int64_t i = 0; i < n; ++i) ++counts[distinct_of_point(s, uniform_index(rng, n))];
  return make_sample(s.value, counts);
}

double draw_below(const Sample& s, std::size_t j, Rng& rng) {
  return s.value[distinct_of_point(s, uniform_index(rng, s.cum[j]))];
}

bool all_integers(std::span<const double> x) {
  return std::all_of(x.begin(), x.end(),
                     [](double v) { return std::isfinite(v) && std::abs(v) < 0x1p53 && v == std::floor(v); });
}

void validate_values(std::span<const double> x, const std::string& what) {
  std::int64_t nan = 0, inf = 0, zero = 0, negative = 0;
  for (double v : x) {
    if (std::isnan(v))
      ++nan;
    else if (std::isinf(v))
      ++inf;
    else if (v == 0)
      ++zero;
    else if (v < 0)
      ++negative;
  }
  const auto n = static_cast<std::int64_t>(x.size());
  if (nan + inf + zero + negative > 0) {
    std::ostringstream msg;
    msg << what << ": " << (nan + inf + zero + negative) << " of " << n << " values cannot be fitted by a power law (";
    std::string sep;
    const auto part = [&](std::int64_t count, const char* label) {
      if (count) msg << sep << count << " " << label, sep = ", ";
    };
    part(nan, "NaN");
    part(inf, "infinite");
    part(zero, "zero");
    part(negative, "negative");
    msg << "); a power law needs positive finite values: remove or correct them";
    throw InputError(msg.str());
  }
  if (n < kMinValues)
    throw InputError(what + ": only " + std::to_string(n) + " value" + (n == 1 ? "" : "s") +
                     "; a power-law fit needs at least " + std::to_string(kMinValues));
  std::vector<double> sorted(x.begin(), x.end());
  std::sort(sorted.begin(), sorted.end());
  const auto distinct = static_cast<std::size_t>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  if (distinct == 1) {
    std::ostringstream msg;
    msg.precision(17);
    msg << what << ": all " << n << " values are equal (" << sorted[0] << "); there is no distribution to fit";
    throw InputError(msg.str());
  }
  if (distinct < kMinDistinct)
    throw InputError(what + ": the " + std::to_string(n) + " values take only " + std::to_string(distinct) +
                     " distinct values; a power-law fit needs at least " + std::to_string(kMinDistinct));
}

Rng replicate_rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  // Mix (seed, stream, index) into one 64-bit seed; the Rng constructor mixes again with splitmix64.
  auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  std::uint64_t h = mix(seed + 0x9e3779b97f4a7c15ULL);
  h = mix(h ^ (stream * 0xd1b54a32d192ed03ULL + 1));
  h = mix(h ^ (index * 0x8cb92ba72f3d8dd7ULL + 2));
  return Rng(h);
}

}  // namespace frac::analysis
