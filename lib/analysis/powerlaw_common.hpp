#pragma once
// What the continuous and discrete power-law estimators share: the options of the x_min scan, the result
// of one tail fit, the Kolmogorov-Smirnov distance between the tail's empirical CDF and a model CDF
// (exact, with branch-and-bound pruning), and a 1-D minimiser.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace frac::analysis {

// How the KS distance reads the empirical CDF S of a continuous tail of m points.
//   two_sided:  sup_x |S(x) - P(x)|, i.e. both S just below and at each point (CSN's definition);
//   powerlaw_r: max_i |P(x_(i)) - (i-1)/m| over the sorted tail points, as R poweRlaw 0.70 does
//               (at most 1/m smaller); use it to compare with poweRlaw.
// Discrete tails always use sup over the integers k >= k_min of |S(k) - P(K <= k)| (both agree there).
enum class KsConvention { two_sided, powerlaw_r };

struct ScanOptions {
  double xmin = std::numeric_limits<double>::quiet_NaN();  // finite: fixed lower cutoff, no scan
  double xmax = std::numeric_limits<double>::infinity();   // finite: model truncated at xmax (data must lie below)
  std::int64_t min_tail = 10;                              // candidates leaving fewer points in the tail are not tried
  KsConvention ks = KsConvention::two_sided;
};

// One power law fitted to the tail x >= xmin.
struct TailFit {
  bool ok = false;
  std::string failure;    // why not ok
  std::size_t first = 0;  // index in the Sample of the first distinct value in the tail
  double xmin = 0;        // lower cutoff
  double xmax = std::numeric_limits<double>::infinity();
  double alpha = 0;             // exponent of the density p(x) ~ x^-alpha
  double alpha_stderr = 0;      // asymptotic (Fisher) standard error; (alpha-1)/sqrt(n) when untruncated
  double ks = 0;                // KS distance of the tail to the fitted model
  double loglik = 0;            // log-likelihood of the tail
  std::int64_t n_tail = 0;      // points in the tail
  std::int64_t candidates = 0;  // x_min candidates tried (1 when fixed)
};

// Model CDF at one distinct value: `lo` = P(X < value) (discrete: P(K <= k-1)), `hi` = P(X <= value).
struct CdfPair {
  double lo, hi;
};

// KS distance between the tail of a sample that starts at distinct index j (cum = Sample::cum) and a model
// whose CDF at distinct index k is eval(k). shift = 1 pairs hi with (points up to k - 1)/m (poweRlaw),
// shift = 0 with (points up to k)/m. Returns the exact distance when it is below abort_at; otherwise some
// value >= abort_at (the caller only needed to know that this candidate loses). The model CDF must be
// non-decreasing: blocks of values whose deviation provably cannot exceed the running maximum are skipped.
// `hint` (optional, in/out): a distinct index to evaluate first, typically where the previous x_min
// candidate's deviation peaked (neighbouring candidates peak at nearly the same place, so a losing candidate
// is usually recognised after one evaluation); on return, where this candidate's deviation peaked.
template <class Eval>
double ks_distance(const std::vector<std::int64_t>& cum, std::size_t j, int shift, Eval&& eval,
                   double abort_at = std::numeric_limits<double>::infinity(), std::size_t* hint = nullptr) {
  const std::size_t last = cum.size() - 2;  // last distinct index
  const std::int64_t c0 = cum[j];
  const double m = static_cast<double>(cum.back() - c0);
  const auto s_lo = [&](std::size_t k) { return static_cast<double>(cum[k] - c0) / m; };
  const auto s_hi = [&](std::size_t k) { return static_cast<double>(cum[k + 1] - c0 - shift) / m; };
  double best = 0;
  std::size_t argmax = j;
  bool stop = false;
  const auto visit = [&](std::size_t k) {
    const CdfPair p = eval(k);
    const double d = std::max(std::abs(p.lo - s_lo(k)), std::abs(p.hi - s_hi(k)));
    if (d > best) best = d, argmax = k;
    if (best >= abort_at) stop = true;
    return p;
  };
  // Upper bound of the deviation at the distinct values strictly between a and b.
  const auto bound = [&](std::size_t a, const CdfPair& pa, std::size_t b, const CdfPair& pb) {
    return std::max(static_cast<double>(cum[b] - c0) / m - pa.hi, pb.lo - static_cast<double>(cum[a + 1] - c0) / m);
  };
  const auto refine = [&](auto& self, std::size_t a, CdfPair pa, std::size_t b, CdfPair pb) -> void {
    if (stop || b - a < 2 || bound(a, pa, b, pb) <= best) return;
    if (b - a <= 4) {
      for (std::size_t k = a + 1; k < b && !stop; ++k) visit(k);
      return;
    }
    const std::size_t mid = a + (b - a) / 2;
    const CdfPair pm = visit(mid);
    if (stop) return;
    // The half that may hold the larger deviation first: it raises `best` and prunes the other.
    if (bound(a, pa, mid, pm) >= bound(mid, pm, b, pb)) {
      self(self, a, pa, mid, pm);
      self(self, mid, pm, b, pb);
    } else {
      self(self, mid, pm, b, pb);
      self(self, a, pa, mid, pm);
    }
  };
  const auto finish = [&] {
    if (hint) *hint = argmax;
    return best;
  };
  if (hint && *hint > j && *hint < last) {
    visit(*hint);
    if (stop) return finish();
  }
  const CdfPair pa = visit(j);
  if (stop || last == j) return finish();
  const CdfPair pb = visit(last);
  if (stop) return finish();
  refine(refine, j, pa, last, pb);
  return finish();
}

// Brent's method (netlib fmin) for the minimum of f on [a, b] (f unimodal there); no bracket needed.
double minimise_1d(const std::function<double(double)>& f, double a, double b, double tol = 1e-10);

// Solves E[t] = mean for the truncated exponential density ~ exp(-c t) on [0, L] (L may be infinite):
// the MLE of c. Used by the truncated power law (t = ln x/xmin) and the truncated exponential.
double truncated_exponential_rate(double mean, double L);
// E[t] and Var[t] of that density, and ln of its normaliser int_0^L exp(-c t) dt.
double truncated_exponential_mean(double c, double L);
double truncated_exponential_var(double c, double L);
double truncated_exponential_lognorm(double c, double L);

// Turns GSL's abort-on-error handler off (once): we check the status of every *_e call ourselves.
void quiet_gsl();

// The x_min scan both estimators share (Clauset, Shalizi and Newman 2009): every distinct value j of
// the sorted sample `s` that leaves at least `min_tail` points and 3 distinct values is a candidate; the
// one whose fit has the smallest KS distance wins. ks_at(j, best_ks, hint) returns that distance (or
// anything ≥ best_ks when the candidate provably loses, +inf when its fit is invalid); fit_at(j) fits the
// winner in full. `symbol` names the cutoff in failure messages (x_min, k_min).
template <class SampleT, class KsAt, class FitAt>
TailFit scan_xmin(const SampleT& s, std::int64_t min_tail, const std::string& symbol, KsAt&& ks_at, FitAt&& fit_at) {
  const std::size_t K = s.distinct();
  double best_ks = std::numeric_limits<double>::infinity();
  std::size_t best = K;
  std::int64_t tried = 0;
  std::size_t hint = 0;  // where the previous candidate's KS deviation peaked
  for (std::size_t j = 0; j + 2 < K; ++j) {
    if (s.tail(j) < min_tail) break;  // tails only shrink with j
    ++tried;
    const double d = ks_at(j, best_ks, &hint);
    if (d < best_ks) best_ks = d, best = j;
  }
  if (best == K) {
    TailFit f;
    f.candidates = tried;
    f.failure = tried ? "no " + symbol + " candidate gave a valid fit"
                      : "no " + symbol + " candidate leaves " + std::to_string(min_tail) +
                            " points and 3 distinct values in the tail";
    return f;
  }
  TailFit f = fit_at(best);
  f.candidates = tried;
  return f;
}

}  // namespace frac::analysis
