#include "analysis/powerlaw_gof.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <tuple>

#include "analysis/powerlaw_continuous.hpp"
#include "analysis/powerlaw_discrete.hpp"

namespace frac::analysis {

const char* model_name(Model m) { return m == Model::continuous ? "continuous" : "discrete"; }

TailFit fit_model(Model model, const Sample& s, const ScanOptions& opt) {
  return model == Model::continuous ? fit_continuous(s, opt) : fit_discrete(s, opt);
}

std::vector<double> draw_model(Model model, const TailFit& fit, std::size_t n, Rng& rng) {
  std::vector<double> x(n);
  if (model == Model::continuous) {
    for (auto& v : x) v = draw_continuous(fit.xmin, fit.alpha, fit.xmax, rng);
  } else {
    const DiscreteSampler sampler(fit.xmin, fit.alpha, fit.xmax);
    for (auto& v : x) v = sampler.draw(rng);
  }
  return x;
}

void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& body) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, count));
  if (threads <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&] {
      for (std::size_t i; (i = next.fetch_add(1)) < count;) {
        try {
          body(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(error_mutex);
          if (!error) error = std::current_exception();
          next = count;
        }
      }
    });
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

namespace {

std::uint64_t stream_id(Model model, int purpose) {
  return (model == Model::continuous ? 16u : 32u) + static_cast<unsigned>(purpose);
}

// Mean and sample standard deviation of the finite entries, in index order.
std::pair<double, double> mean_std(const std::vector<double>& v) {
  double sum = 0;
  std::size_t n = 0;
  for (double x : v)
    if (std::isfinite(x)) sum += x, ++n;
  if (n == 0) return {std::nan(""), std::nan("")};
  const double mean = sum / static_cast<double>(n);
  double ss = 0;
  for (double x : v)
    if (std::isfinite(x)) ss += (x - mean) * (x - mean);
  return {mean, n > 1 ? std::sqrt(ss / static_cast<double>(n - 1)) : std::nan("")};
}

}  // namespace

BootstrapResult bootstrap_uncertainty(Model model, const Sample& s, const ScanOptions& opt, int samples,
                                      std::uint64_t seed, unsigned threads) {
  BootstrapResult r;
  r.samples = std::max(samples, 0);
  const auto B = static_cast<std::size_t>(r.samples);
  r.alpha.assign(B, std::nan(""));
  r.xmin.assign(B, std::nan(""));
  r.n_tail.assign(B, 0);
  parallel_for(B, threads, [&](std::size_t b) {
    Rng rng = replicate_rng(seed, stream_id(model, 1), b);
    const Sample t = resample(s, rng);
    if (t.distinct() < kMinDistinct) return;
    const TailFit f = fit_model(model, t, opt);
    if (!f.ok) return;
    r.alpha[b] = f.alpha;
    r.xmin[b] = f.xmin;
    r.n_tail[b] = f.n_tail;
  });
  double tail_sum = 0;
  for (std::size_t b = 0; b < B; ++b) {
    if (std::isfinite(r.alpha[b]))
      tail_sum += static_cast<double>(r.n_tail[b]);
    else
      ++r.failed;
  }
  std::tie(r.alpha_mean, r.alpha_std) = mean_std(r.alpha);
  std::tie(r.xmin_mean, r.xmin_std) = mean_std(r.xmin);
  r.n_tail_mean = r.samples > r.failed ? tail_sum / (r.samples - r.failed) : std::nan("");
  return r;
}

GofResult gof_pvalue(Model model, const Sample& s, const TailFit& fit, const ScanOptions& opt, int samples,
                     std::uint64_t seed, unsigned threads) {
  GofResult r;
  r.samples = std::max(samples, 0);
  const auto S = static_cast<std::size_t>(r.samples);
  r.ks.assign(S, std::nan(""));
  const std::int64_t n = s.n();
  const double p_tail = static_cast<double>(fit.n_tail) / static_cast<double>(n);
  std::unique_ptr<DiscreteSampler> sampler;
  if (model == Model::discrete) sampler = std::make_unique<DiscreteSampler>(fit.xmin, fit.alpha, fit.xmax);
  parallel_for(S, threads, [&](std::size_t k) {
    Rng rng = replicate_rng(seed, stream_id(model, 2), k);
    std::vector<double> x(static_cast<std::size_t>(n));
    for (auto& v : x) {
      if (fit.first == 0 || rng.uniform() < p_tail) {
        v = model == Model::continuous ? draw_continuous(fit.xmin, fit.alpha, fit.xmax, rng) : sampler->draw(rng);
      } else {
        v = draw_below(s, fit.first, rng);
      }
    }
    const Sample t = make_sample(std::move(x));
    if (t.distinct() < kMinDistinct) return;
    const TailFit f = fit_model(model, t, opt);
    if (f.ok) r.ks[k] = f.ks;
  });
  std::int64_t above = 0, valid = 0;
  for (double d : r.ks) {
    if (!std::isfinite(d)) {
      ++r.failed;
      continue;
    }
    ++valid;
    if (d >= fit.ks) ++above;
  }
  r.p = valid ? static_cast<double>(above) / static_cast<double>(valid) : std::nan("");
  return r;
}

}  // namespace frac::analysis
