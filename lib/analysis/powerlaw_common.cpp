#include "analysis/powerlaw_common.hpp"

#include <gsl/gsl_errno.h>

#include <cfloat>
#include <mutex>

namespace frac::analysis {

double minimise_1d(const std::function<double(double)>& f, double a, double b, double tol) {
  // Brent (1973), "Algorithms for minimization without derivatives", as in netlib's fmin.
  const double c = 0.5 * (3.0 - std::sqrt(5.0));
  const double eps = std::sqrt(DBL_EPSILON);
  double v = a + c * (b - a), w = v, x = v, e = 0.0, d = 0.0;
  double fx = f(x), fv = fx, fw = fx;
  for (int iter = 0; iter < 500; ++iter) {
    const double xm = 0.5 * (a + b);
    const double tol1 = eps * std::abs(x) + tol / 3.0;
    const double tol2 = 2.0 * tol1;
    if (std::abs(x - xm) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol1) {
      double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0)
        p = -p;
      else
        q = -q;
      r = e;
      e = d;
      if (!(std::abs(p) >= std::abs(0.5 * q * r) || p <= q * (a - x) || p >= q * (b - x))) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = std::copysign(tol1, xm - x);
        golden = false;
      }
    }
    if (golden) {
      e = (x < xm) ? b - x : a - x;
      d = c * e;
    }
    const double u = x + (std::abs(d) >= tol1 ? d : std::copysign(tol1, d));
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return x;
}

double truncated_exponential_mean(double c, double L) {
  if (std::isinf(L)) return 1.0 / c;
  if (std::abs(c * L) < 1e-6) return L / 2 - c * L * L / 12;
  return 1.0 / c - L / std::expm1(c * L);
}

double truncated_exponential_var(double c, double L) {
  if (std::isinf(L)) return 1.0 / (c * c);
  const double y = c * L / 2;
  if (std::abs(y) < 1e-2) return L * L * (1.0 / 12 - y * y / 60 + y * y * y * y / 378);
  const double s = std::sinh(y);
  return 1.0 / (c * c) - L * L / (4 * s * s);
}

double truncated_exponential_lognorm(double c, double L) {
  if (std::isinf(L)) return -std::log(c);
  if (std::abs(c * L) < 1e-8) return std::log(L) - c * L / 2;
  if (c > 0) return std::log(-std::expm1(-c * L)) - std::log(c);
  return -c * L + std::log(-std::expm1(c * L)) - std::log(-c);
}

double truncated_exponential_rate(double mean, double L) {
  if (std::isinf(L)) return 1.0 / mean;
  // E_c[t] decreases from L (c -> -inf) to 0 (c -> +inf); E <= 1/c for c > 0 and, by the reflection
  // t -> L - t, E >= L + 1/c for c < 0: so the root lies in [lo, hi].
  double lo = -(2.0 / (L - mean) + 1.0), hi = 2.0 / mean + 1.0;
  for (int iter = 0; iter < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(lo) + std::abs(hi)); ++iter) {
    const double mid = 0.5 * (lo + hi);
    (truncated_exponential_mean(mid, L) > mean ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void quiet_gsl() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

}  // namespace frac::analysis
