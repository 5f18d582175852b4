#include "analysis/log_histogram.hpp"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace frac::analysis {
namespace {
double edge(double j, double b) { return std::pow(10.0, j / b); }
}  // namespace

LogHistogram log_histogram(std::span<const double> x, const LogHistogramOptions& opt) {
  if (x.empty()) throw std::invalid_argument("log_histogram: no values");
  if (!(opt.bins_per_decade > 0) || !std::isfinite(opt.bins_per_decade))
    throw std::invalid_argument("log_histogram: bins per decade must be positive");
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (double v : x) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("log_histogram: values must be positive and finite");
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  const double b = opt.bins_per_decade;
  LogHistogram h;
  h.bins_per_decade = b;
  h.integer_data = opt.integer_data;
  h.n_total = static_cast<std::int64_t>(x.size());
  double j0 = std::floor(b * std::log10(lo));
  while (edge(j0, b) > lo) j0 -= 1;
  while (edge(j0 + 1, b) <= lo) j0 += 1;
  double j1 = j0 + 1;
  while (edge(j1, b) <= hi) j1 += 1;
  const auto K = static_cast<std::size_t>(j1 - j0);
  for (std::size_t k = 0; k <= K; ++k) h.edges.push_back(edge(j0 + static_cast<double>(k), b));
  h.count.assign(K, 0);
  for (double v : x) {
    auto k = static_cast<std::size_t>(std::clamp(std::floor(b * std::log10(v)) - j0, 0.0, static_cast<double>(K - 1)));
    while (k > 0 && v < h.edges[k]) --k;
    while (k + 1 < K && v >= h.edges[k + 1]) ++k;
    ++h.count[k];
  }
  for (std::size_t k = 0; k < K; ++k) {
    const double a = h.edges[k], c = h.edges[k + 1];
    if (opt.integer_data) {
      const double first = std::ceil(a), last = std::ceil(c) - 1;  // integers in [a, c)
      h.width.push_back(std::max(0.0, last - first + 1));
      h.center.push_back(last >= first ? std::sqrt(first * last) : std::sqrt(a * c));
    } else {
      h.width.push_back(c - a);
      h.center.push_back(std::sqrt(a * c));
    }
    h.density.push_back(h.width[k] > 0 ? static_cast<double>(h.count[k]) / (static_cast<double>(h.n_total) * h.width[k]) : 0.0);
  }
  return h;
}

LogSlopeFit fit_log_slope(const LogHistogram& h, const LogSlopeOptions& opt) {
  LogSlopeFit f;
  f.used.assign(h.size(), 0);
  std::vector<double> xs, ys, ws;
  for (std::size_t k = 0; k < h.size(); ++k) {
    double a = h.edges[k], c = h.edges[k + 1];
    if (h.integer_data) a = std::ceil(a), c = std::ceil(c) - 1;  // first and last integer
    const bool inside = a >= opt.fit_min * (1 - 1e-12) && c <= opt.fit_max * (1 + 1e-12);
    if (!inside || h.count[k] < std::max<std::int64_t>(opt.min_count, 1) || !(h.width[k] > 0)) continue;
    f.used[k] = 1;
    xs.push_back(std::log(h.center[k]));
    ys.push_back(std::log(h.density[k]));
    ws.push_back(opt.weighted ? static_cast<double>(h.count[k]) : 1.0);
    if (f.n_bins == 0) f.fit_min = h.edges[k];
    f.fit_max = h.edges[k + 1];
    ++f.n_bins;
  }
  if (f.n_bins < 3) {
    f.slope = f.slope_stderr = f.intercept = f.intercept_stderr = f.chi2_per_dof = std::numeric_limits<double>::quiet_NaN();
    return f;
  }
  double c0, c1, cov00, cov01, cov11, chi2;
  gsl_fit_wlinear(xs.data(), 1, ws.data(), 1, ys.data(), 1, xs.size(), &c0, &c1, &cov00, &cov01, &cov11, &chi2);
  const double dof = f.n_bins - 2;
  f.chi2_per_dof = chi2 / dof;
  // Unweighted: the weights carry no variance, so the scatter sets the scale.
  const double scale = opt.weighted ? std::max(1.0, f.chi2_per_dof) : f.chi2_per_dof;
  f.slope = c1;
  f.intercept = c0;
  f.slope_stderr = std::sqrt(cov11 * scale);
  f.intercept_stderr = std::sqrt(cov00 * scale);
  f.ok = true;
  return f;
}

}  // namespace frac::analysis
