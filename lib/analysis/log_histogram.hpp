#pragma once
// Log-binned density histogram and the weighted least-squares slope of log density against log size: the
// classical way fragmentation papers estimate the exponent of F(m) ~ m^-beta. Standalone (fragment-count
// uses it too). Bins are [10^(j/b), 10^((j+1)/b)) for integer j, b bins per decade, so histograms of
// different samples share their edges. density = count / (n * width): an estimate of the probability density,
// whose log-log slope is -beta (not the slope of counts per log bin, which is 1 - beta).
// Clustered values: fragments of k cells have masses near k times the mean cell mass u, and log bins of
// ratio 1.58 hold one such cluster or two in turn, so the density zig-zags at small masses. With a cluster
// unit u (the mean cell mass; 1 for integer data) the edges are u 10^(j/b), and every one above u/2 moves to
// the half-multiple (ceil(10^(j/b)) - 1/2) u, halfway between two clusters: each bin holds whole clusters,
// its width is their number times u, and bins that would hold no cluster merge into their neighbour
// (in units of u: [0.5, 1.5) [1.5, 2.5) [2.5, 3.5) [3.5, 6.5) [6.5, 9.5) [9.5, 15.5) ... at 5 per decade).
// Known biases (CSN 2009 section 3.1, Goldstein et al. 2004): empty bins are dropped, sparse tail bins pull
// the slope, log(count) is biased for small counts; use the MLE for the exponent, this for comparison.
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace frac::analysis {

struct LogHistogramOptions {
  double bins_per_decade = 5;
  // Integer data (cell counts): the cluster unit is 1, so a bin's width is the number of integers in it and
  // its centre the geometric mean of its first and last integer.
  bool integer_data = false;
  // Cluster unit u for real values that cluster near whole multiples of u (fragment masses: the mean cell
  // mass); 0: plain log bins. Ignored for integer data (u = 1).
  double cluster_unit = 0;
};

struct LogHistogram {
  double bins_per_decade = 5;
  bool integer_data = false;
  double cluster_unit = 0;          // u the edges were moved to half-multiples of (1 for integer data; 0: none)
  std::int64_t n_total = 0;         // values binned (all of them)
  std::vector<double> edges;        // K+1 edges, ascending
  std::vector<std::int64_t> count;  // K
  std::vector<double> width;        // K: edge difference (= clusters in the bin times u)
  std::vector<double> center;       // K: geometric centre of the bin; with clusters, of its first and last one
  std::vector<double> density;      // K: count / (n_total * width); 0 for empty bins
  std::size_t size() const { return count.size(); }
};

// Clustered bins: the first and last cluster index k (value ~ k u) that bin k holds; last < first when it
// holds none (a bin below u/2). Throws std::logic_error for a histogram without clusters.
std::pair<double, double> clusters_in_bin(const LogHistogram& h, std::size_t k);

// Bins positive finite values (throws std::invalid_argument for others, or no values).
LogHistogram log_histogram(std::span<const double> x, const LogHistogramOptions& opt = {});

struct LogSlopeOptions {
  double fit_min = 0;  // use only bins lying wholly in [fit_min, fit_max] (clustered: whose clusters k u do)
  double fit_max = std::numeric_limits<double>::infinity();
  std::int64_t min_count = 1;  // bins with fewer counts are left out (empty bins always: log 0)
  bool weighted = true;        // weights = counts (Var ln density ~ 1/count); false: ordinary least squares
};

struct LogSlopeFit {
  bool ok = false;          // at least 3 bins (otherwise the numbers below are NaN)
  double slope = 0;         // d ln(density) / d ln(x); the density exponent is -slope
  double slope_stderr = 0;  // from the weights (Poisson counts), scaled up by sqrt(chi2/dof) when that exceeds 1
  double intercept = 0;     // ln density at x = 1
  double intercept_stderr = 0;
  double chi2_per_dof = 0;          // of the weighted fit; ~1 when counting noise explains the scatter
  int n_bins = 0;                   // bins used
  double fit_min = 0, fit_max = 0;  // range actually covered by the bins used
  std::vector<std::uint8_t> used;   // per bin: 1 when in the fit
};

// Straight line through (ln center, ln density) of the selected bins.
LogSlopeFit fit_log_slope(const LogHistogram& h, const LogSlopeOptions& opt = {});

}  // namespace frac::analysis
