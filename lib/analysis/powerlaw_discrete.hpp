#pragma once
// Discrete power law p(k) = k^-alpha / zeta(alpha, kmin) on integers k >= kmin (CSN 2009 eq. 2.4), with the
// Hurwitz zeta function of GSL; optionally truncated at kmax (normaliser zeta(alpha,kmin) - zeta(alpha,kmax+1)).
// Exact MLE by a 1-D maximisation of the log-likelihood (concave in alpha; CSN eq. 3.5), its Fisher
// standard error (CSN eq. 3.6), the KS scan over kmin candidates, and an exact sampler (inversion of the CCDF).
#include <cstddef>
#include <limits>
#include <vector>

#include "analysis/powerlaw_common.hpp"
#include "analysis/powerlaw_sample.hpp"
#include "core/rng.hpp"

namespace frac::analysis {

// Range searched for the discrete exponent (the Hurwitz zeta needs alpha > 1).
inline constexpr double kDiscreteAlphaMin = 1.0 + 1e-7;
inline constexpr double kDiscreteAlphaMax = 20.0;

// MLE of the tail starting at distinct index j with cutoff kmin (an integer, value[j-1] < kmin <= value[j]).
// The sample must be integer and lie below xmax. See fit_continuous_at for abort_at.
TailFit fit_discrete_at(const Sample& s, std::size_t j, double kmin, double xmax, KsConvention ks,
                        double abort_at = std::numeric_limits<double>::infinity());

// The KS scan over the distinct values (all but the two largest, leaving opt.min_tail points), or opt.xmin.
TailFit fit_discrete(const Sample& s, const ScanOptions& opt);

// ln of sum_{k=q}^{kmax} k^-alpha (kmax infinite: ln zeta(alpha, q)); NaN when GSL cannot evaluate it.
double log_zeta_sum(double alpha, double q, double kmax = std::numeric_limits<double>::infinity());
double discrete_logpmf(double k, double kmin, double alpha, double kmax = std::numeric_limits<double>::infinity());
// P(K <= k).
double discrete_cdf(double k, double kmin, double alpha, double kmax = std::numeric_limits<double>::infinity());

// Exact draws from the discrete power law: a table of the CCDF near kmin, bisection on the Hurwitz zeta beyond.
class DiscreteSampler {
 public:
  DiscreteSampler(double kmin, double alpha, double kmax = std::numeric_limits<double>::infinity());
  double draw(Rng& rng) const;

 private:
  double ccdf(double k) const;  // P(K >= k)
  double kmin_, alpha_, kmax_, zmax_, z_;
  std::vector<double> table_;  // table_[i] = P(K >= kmin + i)
  double table_end_;           // P(K >= kmin + table_.size())
};

}  // namespace frac::analysis
