#include "analysis/powerlaw_spread.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "analysis/powerlaw.hpp"
#include "analysis/powerlaw_gof.hpp"
#include "core/error.hpp"

namespace frac::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Estimates {
  double mle = kNaN, logbin = kNaN;
};

// Both estimates on one subsample, fitted as the pooled sample was; NaN for one that cannot be made.
Estimates estimate(const std::vector<double>& x, const FitReport& pooled) {
  Estimates e;
  const FitOptions& opt = pooled.options;
  std::vector<double> kept;
  for (double v : x)
    if (v <= opt.scan.xmax) kept.push_back(v);
  try {
    validate_values(kept, "subsample");
  } catch (const InputError&) {
    return e;
  }
  const Model model = pooled.primary_result().model;
  const TailFit f = fit_model(model, make_sample(kept), opt.scan);
  if (f.ok) e.mle = f.alpha;
  const LogHistogram h =
      log_histogram(kept, {pooled.histogram.bins_per_decade, pooled.integer_data, pooled.histogram.cluster_unit});
  const LogSlopeFit s = fit_log_slope(h, pooled.logbin_range);
  if (s.ok) e.logbin = -s.slope;
  return e;
}

}  // namespace

EstimateSpread summarise_spread(std::vector<double> per_input, std::vector<double> leave_one_out) {
  EstimateSpread s;
  double sum = 0, sum2 = 0;
  for (double v : per_input)
    if (!std::isnan(v)) ++s.n_ok, sum += v;
  s.mean = s.n_ok ? sum / s.n_ok : kNaN;
  for (double v : per_input)
    if (!std::isnan(v)) sum2 += (v - s.mean) * (v - s.mean);
  s.stderr_mean = s.n_ok >= 2 ? std::sqrt(sum2 / (s.n_ok - 1) / s.n_ok) : kNaN;
  const auto n = static_cast<double>(leave_one_out.size());
  const double loo_mean = std::accumulate(leave_one_out.begin(), leave_one_out.end(), 0.0) / n;
  double loo2 = 0;
  for (double v : leave_one_out) loo2 += (v - loo_mean) * (v - loo_mean);
  s.jackknife_stderr = n >= 2 ? std::sqrt((n - 1) / n * loo2) : kNaN;  // NaN propagates from a failed fit
  s.per_input = std::move(per_input);
  s.leave_one_out = std::move(leave_one_out);
  return s;
}

InputSpread input_spread(std::span<const double> values, std::span<const std::size_t> sizes, const FitReport& pooled) {
  if (std::accumulate(sizes.begin(), sizes.end(), std::size_t{0}) != values.size())
    throw std::invalid_argument("input_spread: the input sizes do not add up to the pooled values");
  InputSpread r;
  if (sizes.size() < 2) return r;
  r.inputs = static_cast<int>(sizes.size());
  std::vector<double> mle_one, mle_loo, logbin_one, logbin_loo;
  std::size_t begin = 0;
  for (std::size_t size : sizes) {
    const auto first = values.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = first + static_cast<std::ptrdiff_t>(size);
    const Estimates one = estimate(std::vector<double>(first, last), pooled);
    std::vector<double> rest(values.begin(), first);
    rest.insert(rest.end(), last, values.end());
    const Estimates loo = estimate(rest, pooled);
    mle_one.push_back(one.mle), logbin_one.push_back(one.logbin);
    mle_loo.push_back(loo.mle), logbin_loo.push_back(loo.logbin);
    begin += size;
  }
  r.mle = summarise_spread(std::move(mle_one), std::move(mle_loo));
  r.logbin = summarise_spread(std::move(logbin_one), std::move(logbin_loo));
  return r;
}

}  // namespace frac::analysis
