#pragma once
// Likelihood-ratio tests of the fitted power law against alternatives on the same tail (CSN 2009 section 5):
//   exponential  p ~ exp(-lambda x)                  non-nested: Vuong's test
//   lognormal    p ~ x^-1 exp(-(ln x - mu)^2/2s^2)  non-nested: Vuong's test
//   cutoff       p ~ x^-alpha exp(-lambda x)         nests the power law (lambda = 0): chi^2_1 test
// Each alternative is fitted by maximum likelihood on x >= xmin (and <= xmax when the power law is truncated),
// normalised there. Discrete tails use the discrete versions: geometric, the lognormal with continuity
// correction (P(k-1/2 < X <= k+1/2), as R poweRlaw), and k^-alpha exp(-lambda k) normalised by its sum.
// R = sum_i [ln p_PL(x_i) - ln p_alt(x_i)]: R > 0 favours the power law, R < 0 the alternative.
#include <string>
#include <vector>

#include "analysis/powerlaw_common.hpp"
#include "analysis/powerlaw_gof.hpp"
#include "analysis/powerlaw_sample.hpp"

namespace frac::analysis {

struct Comparison {
  std::string alternative;  // "exponential", "lognormal", "cutoff"
  bool nested = false;      // true for the cutoff
  bool ok = false;
  std::string failure;
  std::vector<std::string> param_names;
  std::vector<double> params;  // fitted parameters of the alternative
  double loglik_powerlaw = 0, loglik_alternative = 0;
  double R = 0;         // log-likelihood ratio, power law minus alternative
  double z = 0;         // normalised ratio R / (s sqrt(n)), s = sample sd of the pointwise ratios (Vuong)
  double p = 1;         // non-nested: two-sided Vuong p = erfc(|z|/sqrt 2); nested: 0.5 Q_chi2_1(-2R) (1 when R >= 0)
  std::string favours;  // "power_law", the alternative's name, or "neither" (p >= significance)
};

// All three alternatives, for the tail of `fit` (fit.first onwards) of sample s.
std::vector<Comparison> compare_alternatives(Model model, const Sample& s, const TailFit& fit,
                                             double significance = 0.1);
Comparison compare_one(Model model, const Sample& s, const TailFit& fit, const std::string& alternative,
                       double significance = 0.1);

// ln of int_a^b x^-alpha exp(-lambda x) dx (b may be infinite; lambda >= 0), by adaptive quadrature.
double log_cutoff_integral(double alpha, double lambda, double a, double b);

// ln of sum_{k=kmin}^{kmax} k^-alpha exp(-lambda k) (kmax may be infinite): direct sum near kmin, the
// midpoint-rule integral beyond kmin + 1000 (relative error below 1e-7).
double log_cutoff_sum(double alpha, double lambda, double kmin, double kmax);

// Minimises f by the Nelder-Mead simplex (GSL nmsimplex2) from x0 with initial steps `step`.
std::vector<double> nelder_mead(const std::function<double(const std::vector<double>&)>& f, std::vector<double> x0,
                                const std::vector<double>& step, int max_iter = 2000, double size_tol = 1e-8);

}  // namespace frac::analysis
