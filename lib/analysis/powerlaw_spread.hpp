#pragma once
// The spread of a pooled fit over its inputs (the seeds of an experiment): each input fitted alone (the
// mean and its standard error over inputs: the error the classical papers quote for a slope averaged over
// lattice realisations) and the pooled sample refitted with each input left out in turn (the jackknife
// error of the pooled estimate, from the same input-to-input spread). Both estimators: the primary maximum
// likelihood fit (x_min scanned anew for every subsample) and the log-binned slope over the pooled fit's
// range, on histograms with the pooled fit's edges.
#include <cstddef>
#include <span>
#include <vector>

namespace frac::analysis {

struct FitReport;  // analysis/powerlaw.hpp, which holds an InputSpread

struct EstimateSpread {
  std::vector<double> per_input;      // the estimate from each input alone (NaN when its fit failed)
  std::vector<double> leave_one_out;  // the pooled estimate without input i (NaN when the fit failed)
  int n_ok = 0;                       // inputs whose own fit succeeded
  double mean = 0;                    // mean of the per-input estimates that exist
  double stderr_mean = 0;             // their standard deviation / sqrt(n_ok) (NaN below 2)
  double jackknife_stderr = 0;        // sqrt((n-1)/n sum (leave_one_out_i - their mean)^2) (NaN if any failed)
};

struct InputSpread {
  int inputs = 0;         // 0: not computed (a single input)
  EstimateSpread mle;     // the primary estimator's alpha
  EstimateSpread logbin;  // -slope of the log-binned density
};

// `values` are the pooled values in input order, sizes[i] of them from input i (the values before any
// --xmax cut: the cut is applied here as in fit_powerlaw). `pooled` is fit_powerlaw's report on them.
InputSpread input_spread(std::span<const double> values, std::span<const std::size_t> sizes, const FitReport& pooled);

// Mean, standard error of the mean and jackknife error of the estimates above (exposed for the tests).
EstimateSpread summarise_spread(std::vector<double> per_input, std::vector<double> leave_one_out);

}  // namespace frac::analysis
