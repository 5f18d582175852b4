#include "analysis/powerlaw_compare.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_sf_erf.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "analysis/powerlaw_continuous.hpp"
#include "analysis/powerlaw_discrete.hpp"

namespace frac::analysis {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kHuge = 1e300;

// The tail x >= xmin of a sample, with the sums the alternatives' likelihoods need.
struct Tail {
  std::vector<double> x, w;  // distinct values and their counts
  double n = 0, xmin = 0, xmax = kInf;
  double sum_ln = 0, sum_x = 0, mean_ln = 0, ss_ln = 0;  // ss_ln = sum (ln x - mean_ln)^2
  bool discrete = false;
};

Tail make_tail(Model model, const Sample& s, const TailFit& fit) {
  Tail t;
  t.discrete = model == Model::discrete;
  t.xmin = fit.xmin;
  t.xmax = fit.xmax;
  long double sl = 0, sx = 0;
  for (std::size_t k = fit.first; k < s.distinct(); ++k) {
    const auto c = static_cast<double>(s.count(k));
    t.x.push_back(s.value[k]);
    t.w.push_back(c);
    t.n += c;
    sl += c * std::log(static_cast<long double>(s.value[k]));
    sx += c * static_cast<long double>(s.value[k]);
  }
  t.sum_ln = static_cast<double>(sl);
  t.sum_x = static_cast<double>(sx);
  t.mean_ln = t.sum_ln / t.n;
  for (std::size_t k = 0; k < t.x.size(); ++k) t.ss_ln += t.w[k] * std::pow(std::log(t.x[k]) - t.mean_ln, 2);
  return t;
}

// ln Q(z), Q the upper tail of the standard normal.
double log_q(double z) {
  if (z == kInf) return -kInf;
  if (z > 0) return gsl_sf_log_erfc(z / M_SQRT2) - M_LN2;
  return std::log1p(-0.5 * std::erfc(-z / M_SQRT2));
}

// ln(Q(z1) - Q(z2)) for z1 < z2, without cancellation.
double log_q_diff(double z1, double z2) {
  if (z1 > 0) {
    const double l1 = log_q(z1);
    return l1 + std::log1p(-std::exp(log_q(z2) - l1));
  }
  if (z2 < 0) return log_q_diff(-z2, -z1);
  return std::log(0.5 * (std::erf(z2 / M_SQRT2) - std::erf(z1 / M_SQRT2)));
}

}  // namespace

double log_cutoff_sum(double alpha, double lambda, double kmin, double kmax) {
  // Direct sum over k < kmin + 1000 (stopped once the rest is provably negligible), then the midpoint rule
  // sum_{k>=K} f(k) ~ int_{K-1/2} f: its relative error ~ f''/(24 f) ~ (alpha/K + lambda)^2 / 24 per term, which
  // matters only while the terms beyond K still count (lambda K < ~40): below 1e-7 overall.
  const double direct_end = std::min(kmax, kmin + 1000.0);
  const auto term = [&](double k) { return -alpha * std::log(k) - lambda * k; };
  const double peak = lambda > 0 && alpha < 0 ? -alpha / lambda : kmin;  // maximum of the terms
  const double shift = term(std::clamp(peak, kmin, direct_end));
  double sum = 0;
  double k = kmin;
  for (; k <= direct_end; k += 1) {
    const double t = std::exp(term(k) - shift);
    sum += t;
    // Past the peak the ratio of successive terms, exp(-lambda) (k/(k+1))^alpha, is at most r: the rest is at
    // most t r / (1 - r).
    if (k >= peak && lambda > 0) {
      const double r = alpha >= 0 ? std::exp(-lambda) : std::exp(-lambda - alpha * std::log1p(1.0 / k));
      if (r < 1 && t * r / (1 - r) < 1e-17 * sum) return shift + std::log(sum);
    }
  }
  double log_total = shift + std::log(sum);
  if (k <= kmax) {
    const double rest = log_cutoff_integral(alpha, lambda, k - 0.5, kmax + 0.5);
    const double hi = std::max(log_total, rest);
    log_total = hi + std::log(std::exp(log_total - hi) + std::exp(rest - hi));
  }
  return log_total;
}

namespace {

struct Alt {
  std::vector<std::string> names;
  std::vector<double> params;
  std::vector<double> logp;  // per distinct tail value
  double loglik = 0;
  bool ok = false;
  std::string failure;
};

double weighted_loglik(const Tail& t, const std::vector<double>& logp) {
  double s = 0;
  for (std::size_t k = 0; k < logp.size(); ++k) s += t.w[k] * logp[k];
  return s;
}

Alt fit_exponential(const Tail& t) {
  Alt a;
  a.names = {"lambda"};
  double ybar = 0;
  for (std::size_t k = 0; k < t.x.size(); ++k) ybar += t.w[k] * (t.x[k] - t.xmin);
  ybar /= t.n;
  if (!(ybar > 0)) {
    a.failure = "all tail values equal xmin";
    return a;
  }
  const double L = t.xmax - t.xmin;
  double lambda;
  std::function<double(double)> logp;
  if (!t.discrete) {
    lambda = truncated_exponential_rate(ybar, L);
    const double ln_norm = truncated_exponential_lognorm(lambda, L);
    logp = [=](double x) { return -lambda * (x - t.xmin) - ln_norm; };
  } else {
    // Geometric on k >= kmin (and <= kmax): p(k) = exp(-lambda (k - kmin)) / sum_y exp(-lambda y).
    const auto ln_norm = [L](double lam) {
      const double untrunc = -std::log(-std::expm1(-lam));
      return std::isinf(L) ? untrunc : untrunc + std::log(-std::expm1(-lam * (L + 1)));
    };
    if (std::isinf(L)) {
      lambda = std::log1p(1.0 / ybar);
    } else {
      const double theta = minimise_1d(
          [&](double th) {
            const double lam = std::exp(th);
            return lam * ybar + ln_norm(lam);
          },
          -30, 10);
      lambda = std::exp(theta);
    }
    const double nrm = ln_norm(lambda);
    logp = [=](double x) { return -lambda * (x - t.xmin) - nrm; };
  }
  a.params = {lambda};
  for (double x : t.x) a.logp.push_back(logp(x));
  a.loglik = weighted_loglik(t, a.logp);
  a.ok = std::isfinite(a.loglik);
  if (!a.ok) a.failure = "the exponential likelihood is not finite";
  return a;
}

Alt fit_lognormal(const Tail& t) {
  Alt a;
  a.names = {"mu", "sigma"};
  const double zlo_x = t.discrete ? t.xmin - 0.5 : t.xmin;
  const double zhi_x = t.discrete ? t.xmax + 0.5 : t.xmax;
  const auto log_norm = [&](double mu, double sigma) {
    const double z1 = (std::log(zlo_x) - mu) / sigma;
    const double z2 = std::isinf(zhi_x) ? kInf : (std::log(zhi_x) - mu) / sigma;
    return log_q_diff(z1, z2);
  };
  const auto logp_at = [&](double x, double mu, double sigma) {
    if (t.discrete)
      return log_q_diff((std::log(x - 0.5) - mu) / sigma, (std::log(x + 0.5) - mu) / sigma) - log_norm(mu, sigma);
    const double z = (std::log(x) - mu) / sigma;
    return -std::log(x) - std::log(sigma) - 0.5 * std::log(2 * M_PI) - 0.5 * z * z - log_norm(mu, sigma);
  };
  const auto neg = [&](const std::vector<double>& p) {
    const double mu = p[0], sigma = std::exp(p[1]);
    if (std::abs(mu - t.mean_ln) > 1e3 || p[1] < -30 || p[1] > 8) return kHuge;
    double ll;
    if (t.discrete) {
      ll = 0;
      for (std::size_t k = 0; k < t.x.size(); ++k) ll += t.w[k] * logp_at(t.x[k], mu, sigma);
    } else {
      const double sz2 = (t.ss_ln + t.n * (t.mean_ln - mu) * (t.mean_ln - mu)) / (sigma * sigma);
      ll = -t.sum_ln - t.n * (std::log(sigma) + 0.5 * std::log(2 * M_PI)) - 0.5 * sz2 - t.n * log_norm(mu, sigma);
    }
    return std::isfinite(ll) ? -ll : kHuge;
  };
  const double sd = std::sqrt(std::max(t.ss_ln / t.n, 1e-6));
  auto best = nelder_mead(neg, {t.mean_ln, std::log(sd)}, {0.5, 0.5});
  // A second start: a wide lognormal below xmin (the shape a power-law tail pulls it towards).
  const auto other = nelder_mead(neg, {std::log(t.xmin) - 2 * sd, std::log(2 * sd)}, {1.0, 0.5});
  if (neg(other) < neg(best)) best = other;
  const double mu = best[0], sigma = std::exp(best[1]);
  a.params = {mu, sigma};
  for (double x : t.x) a.logp.push_back(logp_at(x, mu, sigma));
  a.loglik = weighted_loglik(t, a.logp);
  a.ok = std::isfinite(a.loglik);
  if (!a.ok) a.failure = "the lognormal likelihood is not finite";
  return a;
}

Alt fit_cutoff(const Tail& t, double alpha_pl, double loglik_pl, const std::vector<double>& logp_pl) {
  Alt a;
  a.names = {"alpha", "lambda"};
  const double xtop = t.x.back();
  const double th_lo = std::log(1e-8 / xtop), th_hi = std::log(50.0 / t.xmin);
  const auto log_z = [&](double alpha, double lambda) {
    return t.discrete ? log_cutoff_sum(alpha, lambda, t.xmin, t.xmax)
                      : log_cutoff_integral(alpha, lambda, t.xmin, t.xmax);
  };
  const auto neg = [&](const std::vector<double>& p) {
    const double alpha = p[0];
    if (p[1] < th_lo || p[1] > th_hi || alpha < -10 || alpha > 20) return kHuge;
    const double lambda = std::exp(p[1]);
    const double lz = log_z(alpha, lambda);
    const double nll = alpha * t.sum_ln + lambda * t.sum_x + t.n * lz;
    return std::isfinite(nll) ? nll : kHuge;
  };
  std::vector<double> best = nelder_mead(neg, {alpha_pl, std::log(1e-2 / xtop)}, {0.2, 1.0});
  for (const auto& start : {std::vector<double>{alpha_pl - 0.5, std::log(t.n / t.sum_x)},
                            std::vector<double>{alpha_pl, std::log(1.0 / xtop)}}) {
    const auto other = nelder_mead(neg, start, {0.2, 1.0});
    if (neg(other) < neg(best)) best = other;
  }
  const double alpha = best[0], lambda = std::exp(best[1]);
  const double lz = log_z(alpha, lambda);
  for (double x : t.x) a.logp.push_back(-alpha * std::log(x) - lambda * x - lz);
  a.loglik = weighted_loglik(t, a.logp);
  a.params = {alpha, lambda};
  // The cutoff model contains the power law (lambda -> 0): never report it as worse than the power law.
  if (!std::isfinite(a.loglik) || a.loglik < loglik_pl) {
    a.params = {alpha_pl, 0.0};
    a.logp = logp_pl;
    a.loglik = loglik_pl;
  }
  a.ok = true;
  return a;
}

}  // namespace

double log_cutoff_integral(double alpha, double lambda, double a, double b) {
  quiet_gsl();
  const double T = std::isinf(b) ? kInf : std::log(b / a);
  const double base = (1 - alpha) * std::log(a);
  if (lambda <= 0) return base + truncated_exponential_lognorm(alpha - 1, T);
  // x = a e^t: int_0^T exp(g(t)) dt * exp(-lambda a), g(t) = (1-alpha) t - lambda a (e^t - 1).
  const double bq = lambda * a;
  const auto g = [=](double t) { return (1 - alpha) * t - bq * std::expm1(t); };
  double tpk = alpha < 1 ? std::log((1 - alpha) / bq) : 0.0;
  tpk = std::clamp(tpk, 0.0, std::isinf(T) ? std::max(tpk, 0.0) : T);
  const double gmax = g(tpk);
  double tend = tpk, step = 1.0;
  while (tend < T && g(tend) > gmax - 60) tend += step, step *= 1.3;
  tend = std::min(tend, T);
  if (!(tend > 0)) return base - bq + gmax;
  struct Params {
    double alpha, bq, gmax;
  } par{alpha, bq, gmax};
  gsl_function F;
  F.function = [](double t, void* p) {
    const auto* q = static_cast<Params*>(p);
    return std::exp((1 - q->alpha) * t - q->bq * std::expm1(t) - q->gmax);
  };
  F.params = &par;
  std::unique_ptr<gsl_integration_workspace, void (*)(gsl_integration_workspace*)> ws(
      gsl_integration_workspace_alloc(200), gsl_integration_workspace_free);
  double result = 0, err = 0;
  gsl_integration_qags(&F, 0.0, tend, 0.0, 1e-10, 200, ws.get(), &result, &err);
  return base - bq + gmax + std::log(result);
}

std::vector<double> nelder_mead(const std::function<double(const std::vector<double>&)>& f, std::vector<double> x0,
                                const std::vector<double>& step, int max_iter, double size_tol) {
  quiet_gsl();
  const std::size_t n = x0.size();
  struct Ctx {
    const std::function<double(const std::vector<double>&)>* f;
    std::vector<double> buf;
  } ctx{&f, std::vector<double>(n)};
  gsl_multimin_function fn;
  fn.n = n;
  fn.params = &ctx;
  fn.f = [](const gsl_vector* v, void* p) {
    auto* c = static_cast<Ctx*>(p);
    for (std::size_t i = 0; i < c->buf.size(); ++i) c->buf[i] = gsl_vector_get(v, i);
    return (*c->f)(c->buf);
  };
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> x(gsl_vector_alloc(n), gsl_vector_free),
      ss(gsl_vector_alloc(n), gsl_vector_free);
  for (std::size_t i = 0; i < n; ++i) gsl_vector_set(x.get(), i, x0[i]), gsl_vector_set(ss.get(), i, step[i]);
  std::unique_ptr<gsl_multimin_fminimizer, void (*)(gsl_multimin_fminimizer*)> s(
      gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, n), gsl_multimin_fminimizer_free);
  gsl_multimin_fminimizer_set(s.get(), &fn, x.get(), ss.get());
  for (int iter = 0; iter < max_iter; ++iter) {
    if (gsl_multimin_fminimizer_iterate(s.get()) != GSL_SUCCESS) break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s.get()), size_tol) == GSL_SUCCESS) break;
  }
  for (std::size_t i = 0; i < n; ++i) x0[i] = gsl_vector_get(s->x, i);
  return x0;
}

Comparison compare_one(Model model, const Sample& s, const TailFit& fit, const std::string& alternative,
                       double significance) {
  quiet_gsl();
  Comparison c;
  c.alternative = alternative;
  c.nested = alternative == "cutoff";
  const Tail t = make_tail(model, s, fit);
  std::vector<double> logp_pl;
  for (double x : t.x)
    logp_pl.push_back(model == Model::continuous ? continuous_logpdf(x, fit.xmin, fit.alpha, fit.xmax)
                                                 : discrete_logpmf(x, fit.xmin, fit.alpha, fit.xmax));
  c.loglik_powerlaw = weighted_loglik(t, logp_pl);
  Alt a;
  if (alternative == "exponential")
    a = fit_exponential(t);
  else if (alternative == "lognormal")
    a = fit_lognormal(t);
  else if (alternative == "cutoff")
    a = fit_cutoff(t, fit.alpha, c.loglik_powerlaw, logp_pl);
  else
    throw std::invalid_argument("unknown alternative '" + alternative + "'");
  c.param_names = a.names;
  c.params = a.params;
  if (!a.ok) {
    c.failure = a.failure;
    c.favours = "neither";
    return c;
  }
  c.loglik_alternative = a.loglik;
  c.R = c.loglik_powerlaw - c.loglik_alternative;
  // Vuong: pointwise ratios, their sample standard deviation (n - 1, as poweRlaw).
  const double mean = c.R / t.n;
  double ss = 0;
  for (std::size_t k = 0; k < t.x.size(); ++k) ss += t.w[k] * std::pow(logp_pl[k] - a.logp[k] - mean, 2);
  const double sd = std::sqrt(ss / (t.n - 1));
  c.z = sd > 0 ? std::sqrt(t.n) * mean / sd : 0.0;
  if (c.nested)
    c.p = c.R < 0 ? 0.5 * gsl_cdf_chisq_Q(-2 * c.R, 1) : 1.0;
  else
    c.p = std::erfc(std::abs(c.z) / M_SQRT2);
  c.favours = c.p >= significance ? "neither" : (c.R > 0 ? "power_law" : alternative);
  c.ok = true;
  return c;
}

std::vector<Comparison> compare_alternatives(Model model, const Sample& s, const TailFit& fit, double significance) {
  std::vector<Comparison> out;
  for (const char* alt : {"exponential", "lognormal", "cutoff"})
    out.push_back(compare_one(model, s, fit, alt, significance));
  return out;
}

}  // namespace frac::analysis
