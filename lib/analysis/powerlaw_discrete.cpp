#include "analysis/powerlaw_discrete.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_zeta.h>

#include <algorithm>
#include <cmath>

namespace frac::analysis {
namespace {

double hzeta(double s, double q) {
  gsl_sf_result r;
  if (gsl_sf_hzeta_e(s, q, &r) != GSL_SUCCESS) return std::numeric_limits<double>::quiet_NaN();
  return r.val;
}

// sum_{k >= q} k^-alpha minus the part above kmax.
double zeta_sum(double alpha, double q, double kmax) {
  const double z = hzeta(alpha, q);
  return std::isinf(kmax) ? z : z - hzeta(alpha, kmax + 1);
}

struct Core {
  double alpha = 0, log_z = 0, z = 0, zmax = 0, sum_ln = 0;
  std::int64_t m = 0;
  bool ok = false;
};

Core core_fit(const Sample& s, std::size_t j, double kmin, double kmax) {
  Core c;
  c.m = s.tail(j);
  const double m = static_cast<double>(c.m);
  c.sum_ln = s.suffix_log[j] + m * s.log_ref;
  if (c.m < 2 || s.value.back() == kmin) return c;
  const auto neg_loglik = [&](double a) {
    const double lz = log_zeta_sum(a, kmin, kmax);
    return std::isfinite(lz) ? m * lz + a * c.sum_ln : std::numeric_limits<double>::max();
  };
  c.alpha = minimise_1d(neg_loglik, kDiscreteAlphaMin, kDiscreteAlphaMax, 1e-9);
  c.z = zeta_sum(c.alpha, kmin, kmax);
  c.zmax = std::isinf(kmax) ? 0.0 : hzeta(c.alpha, kmax + 1);
  c.log_z = std::log(c.z);
  c.ok = std::isfinite(c.log_z);
  return c;
}

double core_ks(const Sample& s, std::size_t j, const Core& c, double abort_at, std::size_t* hint = nullptr) {
  const auto eval = [&](std::size_t i) {
    const double u = s.value[i];
    const double lo = 1.0 - (hzeta(c.alpha, u) - c.zmax) / c.z;  // P(K <= u-1)
    return CdfPair{lo, lo + std::pow(u, -c.alpha) / c.z};
  };
  return ks_distance(s.cum, j, 0, eval, abort_at, hint);
}

}  // namespace

double log_zeta_sum(double alpha, double q, double kmax) {
  const double z = zeta_sum(alpha, q, kmax);
  return z > 0 ? std::log(z) : std::numeric_limits<double>::quiet_NaN();
}

double discrete_logpmf(double k, double kmin, double alpha, double kmax) {
  return -alpha * std::log(k) - log_zeta_sum(alpha, kmin, kmax);
}

double discrete_cdf(double k, double kmin, double alpha, double kmax) {
  quiet_gsl();
  if (k < kmin) return 0.0;
  if (k >= kmax) return 1.0;
  return 1.0 - zeta_sum(alpha, std::floor(k) + 1, kmax) / zeta_sum(alpha, kmin, kmax);
}

TailFit fit_discrete_at(const Sample& s, std::size_t j, double kmin, double xmax, KsConvention, double abort_at) {
  quiet_gsl();
  TailFit f;
  f.first = j;
  f.xmin = kmin;
  f.xmax = std::isinf(xmax) ? xmax : std::floor(xmax);
  f.candidates = 1;
  if (j >= s.distinct()) {
    f.failure = "no value at or above xmin";
    return f;
  }
  const Core c = core_fit(s, j, kmin, f.xmax);
  f.n_tail = c.m;
  if (!c.ok) {
    f.failure = c.m < 2 || s.value.back() == kmin ? "the tail holds fewer than two distinct values"
                                                  : "the Hurwitz zeta function could not be evaluated";
    return f;
  }
  f.alpha = c.alpha;
  f.ks = core_ks(s, j, c, abort_at);
  if (f.ks >= abort_at) {
    f.failure = "KS distance above the bound";
    return f;
  }
  const double m = static_cast<double>(c.m);
  // Fisher information per point: d^2 ln Z / d alpha^2 = Var(ln K), by central differences.
  const double h = std::min(1e-3, (c.alpha - 1.0) / 3.0);
  const double var =
      (log_zeta_sum(c.alpha + h, kmin, f.xmax) - 2 * c.log_z + log_zeta_sum(c.alpha - h, kmin, f.xmax)) / (h * h);
  f.alpha_stderr = var > 0 ? 1.0 / std::sqrt(m * var) : std::numeric_limits<double>::quiet_NaN();
  f.loglik = -m * c.log_z - c.alpha * c.sum_ln;
  f.ok = true;
  return f;
}

TailFit fit_discrete(const Sample& s, const ScanOptions& opt) {
  quiet_gsl();
  if (std::isfinite(opt.xmin)) {
    const double kmin = std::ceil(opt.xmin);
    return fit_discrete_at(s, s.first_at_least(kmin), kmin, opt.xmax, opt.ks);
  }
  const double kmax = std::isinf(opt.xmax) ? opt.xmax : std::floor(opt.xmax);
  return scan_xmin(
      s, opt.min_tail, "k_min",
      [&](std::size_t j, double best_ks, std::size_t* hint) {
        const Core c = core_fit(s, j, s.value[j], kmax);
        return c.ok ? core_ks(s, j, c, best_ks, hint) : std::numeric_limits<double>::infinity();
      },
      [&](std::size_t j) { return fit_discrete_at(s, j, s.value[j], opt.xmax, opt.ks); });
}

DiscreteSampler::DiscreteSampler(double kmin, double alpha, double kmax) : kmin_(kmin), alpha_(alpha), kmax_(kmax) {
  quiet_gsl();
  zmax_ = std::isinf(kmax) ? 0.0 : hzeta(alpha, kmax + 1);
  z_ = hzeta(alpha, kmin) - zmax_;
  // CCDF table by recursion P(K >= k+1) = P(K >= k) - k^-alpha / Z (rounding drift ~ size * 1e-16).
  const std::size_t limit = std::isinf(kmax) ? 65536 : static_cast<std::size_t>(std::min(65536.0, kmax - kmin + 1));
  double p = 1.0;
  table_.reserve(limit);
  for (std::size_t i = 0; i < limit && p > 1e-9; ++i) {
    table_.push_back(p);
    p -= std::pow(kmin + static_cast<double>(i), -alpha) / z_;
  }
  table_end_ = std::max(p, 0.0);
  if (!std::isinf(kmax) && kmin + static_cast<double>(table_.size()) > kmax) table_end_ = 0.0;
}

double DiscreteSampler::ccdf(double k) const {
  if (k > kmax_) return 0.0;
  return (hzeta(alpha_, k) - zmax_) / z_;
}

double DiscreteSampler::draw(Rng& rng) const {
  const double v = 1.0 - rng.uniform();  // in (0, 1]
  // The answer is the largest k with P(K >= k) >= v.
  if (v > table_end_) {
    const auto it = std::upper_bound(table_.begin(), table_.end(), v, [](double x, double t) { return x > t; });
    return kmin_ + static_cast<double>(it - table_.begin() - 1);
  }
  double lo = kmin_ + static_cast<double>(table_.size());  // ccdf(lo) >= v
  // Start from the continuous approximation (CSN App. D), then bracket and bisect on the exact CCDF.
  double hi = std::max(lo + 1, std::floor((kmin_ - 0.5) * std::pow(v, -1.0 / (alpha_ - 1.0)) + 0.5) + 1);
  while (hi <= 0x1p52 && ccdf(hi) >= v) lo = hi, hi = 2 * hi;
  if (!std::isinf(kmax_)) hi = std::min(hi, kmax_ + 1);
  while (hi - lo > 1) {
    const double mid = std::floor(0.5 * (lo + hi));
    (ccdf(mid) >= v ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace frac::analysis
