#pragma once
// Continuous power law p(x) = (alpha-1)/xmin (x/xmin)^-alpha on x >= xmin (CSN 2009 eq. 2.2), optionally
// truncated at xmax (then normalised on [xmin, xmax], any real alpha). Maximum likelihood for a given
// xmin (closed form CSN eq. 3.1 when untruncated, a 1-D root otherwise), the scan over xmin candidates
// that minimises the KS distance (CSN section 3.3), and the sampler used by the bootstrap.
#include <cstddef>
#include <limits>

#include "analysis/powerlaw_common.hpp"
#include "analysis/powerlaw_sample.hpp"
#include "core/rng.hpp"

namespace frac::analysis {

// MLE of the tail that starts at distinct index j with lower cutoff xmin (value[j-1] < xmin <= value[j]).
// The sample must lie below xmax. With abort_at finite, returns early (ok = false, ks >= abort_at) as soon as
// the KS distance is known to reach abort_at.
TailFit fit_continuous_at(const Sample& s, std::size_t j, double xmin, double xmax, KsConvention ks,
                          double abort_at = std::numeric_limits<double>::infinity());

// The full procedure: scan the distinct values as xmin candidates (all but the two largest, and only those
// that leave opt.min_tail points), or use opt.xmin when it is finite. Not ok when no candidate qualifies.
TailFit fit_continuous(const Sample& s, const ScanOptions& opt);

// Model functions (alpha > 1 when xmax is infinite).
double continuous_cdf(double x, double xmin, double alpha, double xmax = std::numeric_limits<double>::infinity());
double continuous_logpdf(double x, double xmin, double alpha, double xmax = std::numeric_limits<double>::infinity());
// One draw by inversion of the CDF.
double draw_continuous(double xmin, double alpha, double xmax, Rng& rng);

}  // namespace frac::analysis
