#include "analysis/powerlaw_continuous.hpp"

#include <algorithm>
#include <cmath>

namespace frac::analysis {
namespace {

// CDF of t = ln(x/xmin) under the (truncated) power law with c = alpha - 1 and L = ln(xmax/xmin).
double cdf_t(double t, double c, double L) {
  if (std::isinf(L)) return -std::expm1(-c * t);
  if (std::abs(c * L) < 1e-12) return t / L;
  return std::expm1(-c * t) / std::expm1(-c * L);
}

struct Core {
  double c = 0, L = 0, l0 = 0, sum_t = 0;
  std::int64_t m = 0;
  bool ok = false;
};

// Exponent for the tail starting at j with cutoff xmin: O(1) from the suffix sums (plus a 1-D root when truncated).
Core core_fit(const Sample& s, std::size_t j, double xmin, double xmax) {
  Core k;
  k.m = s.tail(j);
  k.l0 = (xmin == s.value[j]) ? s.log_rel[j] : std::log(xmin) - s.log_ref;
  k.sum_t = s.suffix_log[j] - static_cast<double>(k.m) * k.l0;
  k.L = std::isinf(xmax) ? xmax : std::log(xmax / xmin);
  if (k.m < 2 || !(k.sum_t > 0)) return k;
  const double mean = k.sum_t / static_cast<double>(k.m);
  if (!std::isinf(k.L) && !(mean < k.L)) return k;
  k.c = truncated_exponential_rate(mean, k.L);
  k.ok = std::isfinite(k.c) && (!std::isinf(k.L) || k.c > 0);
  return k;
}

double core_ks(const Sample& s, std::size_t j, const Core& k, KsConvention conv, double abort_at,
               std::size_t* hint = nullptr) {
  const auto eval = [&](std::size_t i) {
    const double p = cdf_t(s.log_rel[i] - k.l0, k.c, k.L);
    return CdfPair{p, p};
  };
  return ks_distance(s.cum, j, conv == KsConvention::powerlaw_r ? 1 : 0, eval, abort_at, hint);
}

}  // namespace

TailFit fit_continuous_at(const Sample& s, std::size_t j, double xmin, double xmax, KsConvention ks, double abort_at) {
  TailFit f;
  f.first = j;
  f.xmin = xmin;
  f.xmax = xmax;
  f.candidates = 1;
  if (j >= s.distinct()) {
    f.failure = "no value at or above xmin";
    return f;
  }
  const Core k = core_fit(s, j, xmin, xmax);
  f.n_tail = k.m;
  if (!k.ok) {
    f.failure = "the tail holds fewer than two distinct values";
    return f;
  }
  f.alpha = 1 + k.c;
  f.ks = core_ks(s, j, k, ks, abort_at);
  if (f.ks >= abort_at) {
    f.failure = "KS distance above the bound";
    return f;
  }
  const double m = static_cast<double>(k.m);
  f.alpha_stderr = 1.0 / std::sqrt(m * truncated_exponential_var(k.c, k.L));
  // ln p(x) = -alpha t - ln xmin - ln N(c), N(c) = int_0^L exp(-c t) dt.
  f.loglik = -f.alpha * k.sum_t - m * std::log(xmin) - m * truncated_exponential_lognorm(k.c, k.L);
  f.ok = true;
  return f;
}

TailFit fit_continuous(const Sample& s, const ScanOptions& opt) {
  if (std::isfinite(opt.xmin)) return fit_continuous_at(s, s.first_at_least(opt.xmin), opt.xmin, opt.xmax, opt.ks);
  return scan_xmin(
      s, opt.min_tail, "x_min",
      [&](std::size_t j, double best_ks, std::size_t* hint) {
        const Core k = core_fit(s, j, s.value[j], opt.xmax);
        return k.ok ? core_ks(s, j, k, opt.ks, best_ks, hint) : std::numeric_limits<double>::infinity();
      },
      [&](std::size_t j) { return fit_continuous_at(s, j, s.value[j], opt.xmax, opt.ks); });
}

double continuous_cdf(double x, double xmin, double alpha, double xmax) {
  if (x <= xmin) return 0.0;
  if (x >= xmax) return 1.0;
  return cdf_t(std::log(x / xmin), alpha - 1, std::isinf(xmax) ? xmax : std::log(xmax / xmin));
}

double continuous_logpdf(double x, double xmin, double alpha, double xmax) {
  const double c = alpha - 1;
  const double L = std::isinf(xmax) ? xmax : std::log(xmax / xmin);
  return -alpha * std::log(x / xmin) - std::log(xmin) - truncated_exponential_lognorm(c, L);
}

double draw_continuous(double xmin, double alpha, double xmax, Rng& rng) {
  const double c = alpha - 1, u = rng.uniform();
  double t;
  if (std::isinf(xmax)) {
    t = -std::log1p(-u) / c;
  } else {
    const double L = std::log(xmax / xmin);
    t = std::abs(c * L) < 1e-12 ? u * L : -std::log1p(u * std::expm1(-c * L)) / c;
  }
  return std::min(xmin * std::exp(t), xmax);
}

}  // namespace frac::analysis
