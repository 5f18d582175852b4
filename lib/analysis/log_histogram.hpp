#pragma once
// Log-binned density histogram and the weighted least-squares slope of log density against log size: the
// classical way fragmentation papers estimate the exponent of F(m) ~ m^-beta. Standalone (fragment-count
// uses it too). Bins are [10^(j/b), 10^((j+1)/b)) for integer j, b bins per decade, so histograms of
// different samples share their edges. density = count / (n * width): an estimate of the probability density,
// whose log-log slope is -beta (not the slope of counts per log bin, which is 1 - beta).
// Known biases (CSN 2009 section 3.1, Goldstein et al. 2004): empty bins are dropped, sparse tail bins pull
// the slope, log(count) is biased for small counts; use the MLE for the exponent, this for comparison.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace frac::analysis {

struct LogHistogramOptions {
  double bins_per_decade = 5;
  // Integer data (cell counts): a bin's width is the number of integers in it (the bin [1, 1.58) holds one
  // integer, width 1, not 0.58), and its centre is the geometric mean of its first and last integer.
  bool integer_data = false;
};

struct LogHistogram {
  double bins_per_decade = 5;
  bool integer_data = false;
  std::int64_t n_total = 0;           // values binned (all of them)
  std::vector<double> edges;          // K+1 edges, ascending
  std::vector<std::int64_t> count;    // K
  std::vector<double> width;          // K: edge difference, or the number of integers in the bin
  std::vector<double> center;         // K: geometric centre of the bin (integer data: of its integers)
  std::vector<double> density;        // K: count / (n_total * width); 0 for empty bins or bins holding no integer
  std::size_t size() const { return count.size(); }
};

// Bins positive finite values (throws std::invalid_argument for others, or no values).
LogHistogram log_histogram(std::span<const double> x, const LogHistogramOptions& opt = {});

struct LogSlopeOptions {
  double fit_min = 0;  // use only bins lying wholly in [fit_min, fit_max] (integer data: whose integers do)
  double fit_max = std::numeric_limits<double>::infinity();
  std::int64_t min_count = 1;  // bins with fewer counts are left out (empty bins always: log 0)
  bool weighted = true;        // weights = counts (Var ln density ~ 1/count); false: ordinary least squares
};

struct LogSlopeFit {
  bool ok = false;         // at least 3 bins (otherwise the numbers below are NaN)
  double slope = 0;        // d ln(density) / d ln(x); the density exponent is -slope
  double slope_stderr = 0; // from the weights (Poisson counts), scaled up by sqrt(chi2/dof) when that exceeds 1
  double intercept = 0;    // ln density at x = 1
  double intercept_stderr = 0;
  double chi2_per_dof = 0; // of the weighted fit; ~1 when counting noise explains the scatter
  int n_bins = 0;          // bins used
  double fit_min = 0, fit_max = 0;  // range actually covered by the bins used
  std::vector<std::uint8_t> used;   // per bin: 1 when in the fit
};

// Straight line through (ln center, ln density) of the selected bins.
LogSlopeFit fit_log_slope(const LogHistogram& h, const LogSlopeOptions& opt = {});

}  // namespace frac::analysis
