#pragma once
// Uncertainty and plausibility of a power-law fit by resampling (CSN 2009 sections 3.5 and 4.1):
//  - non-parametric bootstrap: resample all n points with replacement and redo the whole fit (x_min scan
//    included), so the spread of alpha includes the uncertainty of x_min;
//  - goodness of fit: the semi-parametric bootstrap p-value (synthetic sets of n points, each point with
//    probability n_tail/n from the fitted power law above x_min, otherwise drawn from the observed points
//    below x_min; fitted exactly as the data; p = fraction with a KS distance >= the observed one).
// Replicate r uses its own generator replicate_rng(seed, stream, r): results do not depend on the number
// of threads or their scheduling.
#include <cstdint>
#include <functional>
#include <vector>

#include "analysis/powerlaw_common.hpp"
#include "analysis/powerlaw_sample.hpp"

namespace frac::analysis {

enum class Model { continuous, discrete };
const char* model_name(Model m);  // "continuous" or "discrete"

// fit_continuous or fit_discrete.
TailFit fit_model(Model model, const Sample& s, const ScanOptions& opt);
// n draws from the fitted (possibly truncated) power law.
std::vector<double> draw_model(Model model, const TailFit& fit, std::size_t n, Rng& rng);

struct BootstrapResult {
  int samples = 0;                  // replicates asked for
  int failed = 0;                   // replicates whose fit failed (left out of the statistics)
  std::vector<double> alpha, xmin;  // per replicate (NaN when failed)
  std::vector<std::int64_t> n_tail;
  double alpha_mean = 0, alpha_std = 0, xmin_mean = 0, xmin_std = 0, n_tail_mean = 0;
};
BootstrapResult bootstrap_uncertainty(Model model, const Sample& s, const ScanOptions& opt, int samples,
                                      std::uint64_t seed, unsigned threads = 0);

struct GofResult {
  int samples = 0;
  int failed = 0;
  double p = 0;            // fraction of synthetic KS distances >= the observed one
  std::vector<double> ks;  // per synthetic set (NaN when its fit failed)
};
GofResult gof_pvalue(Model model, const Sample& s, const TailFit& fit, const ScanOptions& opt, int samples,
                     std::uint64_t seed, unsigned threads = 0);

// Runs body(i) for i in [0, count) on `threads` threads (0: all cores); rethrows the first exception.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body);

}  // namespace frac::analysis
