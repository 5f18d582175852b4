#include "analysis/log_histogram.hpp"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace frac::analysis {
namespace {
// Edge j of b per decade: 10^(j/b), or with a cluster unit u, u 10^(j/b) moved halfway between the clusters
// (k - 1/2) u and (k + 1/2) u that surround it (the tolerance keeps an edge on a cluster, 10 u say, below it).
double edge(double j, double b, double u) {
  const double e = std::pow(10.0, j / b);
  return u > 0 && e >= 0.5 ? (std::ceil(e * (1 - 1e-12)) - 0.5) * u : (u > 0 ? u : 1.0) * e;
}
}  // namespace

std::pair<double, double> clusters_in_bin(const LogHistogram& h, std::size_t k) {
  if (!(h.cluster_unit > 0)) throw std::logic_error("clusters_in_bin: the histogram has no cluster unit");
  const double u = h.cluster_unit;
  return {std::ceil(h.edges[k] / u), std::ceil(h.edges[k + 1] / u) - 1};  // k u in [lower, upper)
}

LogHistogram log_histogram(std::span<const double> x, const LogHistogramOptions& opt) {
  if (x.empty()) throw std::invalid_argument("log_histogram: no values");
  if (!(opt.bins_per_decade > 0) || !std::isfinite(opt.bins_per_decade))
    throw std::invalid_argument("log_histogram: bins per decade must be positive");
  if (!(opt.cluster_unit >= 0) || !std::isfinite(opt.cluster_unit))
    throw std::invalid_argument("log_histogram: the cluster unit must be zero or positive");
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (double v : x) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("log_histogram: values must be positive and finite");
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  const double b = opt.bins_per_decade;
  const double u = opt.integer_data ? 1.0 : opt.cluster_unit;
  LogHistogram h;
  h.bins_per_decade = b;
  h.integer_data = opt.integer_data;
  h.cluster_unit = u;
  h.n_total = static_cast<std::int64_t>(x.size());
  double j = std::floor(b * std::log10(lo));
  while (edge(j, b, u) > lo) j -= 1;
  while (edge(j + 1, b, u) <= lo) j += 1;
  h.edges.push_back(edge(j, b, u));
  while (h.edges.back() <= hi) {
    const double e = edge(++j, b, u);
    if (e > h.edges.back()) h.edges.push_back(e);  // edges that fell on the same gap between clusters: one bin
  }
  const std::size_t K = h.edges.size() - 1;
  h.count.assign(K, 0);
  for (double v : x)
    ++h.count[static_cast<std::size_t>(std::upper_bound(h.edges.begin(), h.edges.end(), v) - h.edges.begin() - 1)];
  for (std::size_t k = 0; k < K; ++k) {
    const double a = h.edges[k], c = h.edges[k + 1];
    h.width.push_back(c - a);
    const auto [first, last] = u > 0 ? clusters_in_bin(h, k) : std::pair{1.0, 0.0};
    h.center.push_back(last >= first ? u * std::sqrt(first * last) : std::sqrt(a * c));
    h.density.push_back(static_cast<double>(h.count[k]) / (static_cast<double>(h.n_total) * h.width[k]));
  }
  return h;
}

LogSlopeFit fit_log_slope(const LogHistogram& h, const LogSlopeOptions& opt) {
  LogSlopeFit f;
  f.used.assign(h.size(), 0);
  std::vector<double> xs, ys, ws;
  for (std::size_t k = 0; k < h.size(); ++k) {
    double a = h.edges[k], c = h.edges[k + 1];
    if (h.cluster_unit > 0) {
      const auto [first, last] = clusters_in_bin(h, k);
      if (last >= first) a = first * h.cluster_unit, c = last * h.cluster_unit;
    }
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
    f.slope = f.slope_stderr = f.intercept = f.intercept_stderr = f.chi2_per_dof =
        std::numeric_limits<double>::quiet_NaN();
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
