#pragma once
// powerlaw-fit's library entry point: every estimator of the exponent of a power-law density run side by
// side on one sample (the tool and the tests call this):
//   continuous_mle    CSN 2009: MLE with x_min chosen by minimum KS distance; asymptotic and bootstrap errors;
//                     semi-parametric bootstrap goodness-of-fit p-value
//   discrete_mle      the same with the exact discrete (Hurwitz zeta) likelihood, for integer data
//   log_binned_slope  weighted least-squares slope of the log-binned density histogram (the classical method)
//   comparison        likelihood-ratio tests of the primary fit against exponential, lognormal, cutoff
//   spread            both exponents per pooled input and left out in turn (analysis/powerlaw_spread)
// Exponent convention: every alpha here is the exponent of the probability DENSITY, p(x) ~ x^-alpha. For a
// fragment mass distribution written F(m) ~ m^-beta (number of fragments per unit mass), beta = alpha.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "analysis/log_histogram.hpp"
#include "analysis/powerlaw_common.hpp"
#include "analysis/powerlaw_compare.hpp"
#include "analysis/powerlaw_gof.hpp"
#include "analysis/powerlaw_spread.hpp"

namespace frac::analysis {

struct FitOptions {
  std::string model = "auto";  // primary estimator: auto (discrete for integer data), continuous, discrete
  ScanOptions scan;            // fixed xmin, xmax (upper cutoff), min_tail, KS convention
  int bootstrap = 200;         // non-parametric bootstrap resamples for the uncertainty (0: none)
  int gof_samples = 250;       // synthetic sets for the goodness-of-fit p-value (0: none)
  bool compare = true;         // likelihood-ratio tests against the alternatives
  double significance = 0.1;   // p below this makes a likelihood-ratio test decisive (CSN use 0.1)
  double bins_per_decade = 5;  // log-binned histogram
  // Mean cell mass of fragment masses (0: none): the histogram's edges fall halfway between the masses of
  // fragments of k and k + 1 cells (analysis/log_histogram). Integer data use 1.
  double cell_mass = 0;
  // Lower end of the log-binned slope fit: NaN = the primary MLE's x_min; 0 = all data; else a value.
  double logbin_min = std::numeric_limits<double>::quiet_NaN();
  double logbin_max = std::numeric_limits<double>::infinity();
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all cores; results do not depend on it
};

struct EstimatorResult {
  std::string name;  // "continuous_mle" or "discrete_mle"
  Model model = Model::continuous;
  TailFit fit;
  BootstrapResult bootstrap;
  GofResult gof;
};

struct FitReport {
  std::int64_t n_values = 0;      // values fitted
  std::int64_t n_above_xmax = 0;  // values above --xmax, left out on request (reported, never silent)
  bool integer_data = false;
  std::string primary;                  // name of the primary estimator
  std::vector<EstimatorResult> mle;     // continuous_mle, then discrete_mle for integer data
  std::vector<Comparison> comparisons;  // for the primary estimator's tail
  LogHistogram histogram;               // of all values fitted
  LogSlopeOptions logbin_range;         // the range the log-binned slope was fitted over (x_min resolved)
  LogSlopeFit logbin;
  InputSpread spread;  // over the pooled inputs (add_input_spread; inputs = 0 when not computed)
  FitOptions options;

  const EstimatorResult& primary_result() const;
  const EstimatorResult* find(const std::string& name) const;
};

// UsageError naming the option for a value out of range (significance outside (0, 1), threads beyond
// cli::check_threads, more than 10^6 resamples, NaN bounds, ...).
void check_fit_options(const FitOptions& opt);

// Runs every estimator. Throws InputError (naming `what`) for values a power law cannot take
// (see validate_values), for non-integer values with model = discrete, and when the primary fit finds no
// x_min candidate; UsageError for inconsistent options.
FitReport fit_powerlaw(std::span<const double> values, const FitOptions& opt, const std::string& what = "input");

// One line for humans: "alpha = 2.03 +- 0.05 (bootstrap 0.06), xmin = 1.2, n_tail = 812 of 1000, p = 0.43".
std::string summary_line(const FitReport& r);

}  // namespace frac::analysis
