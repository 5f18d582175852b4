#include "analysis/powerlaw.hpp"

#include <cmath>
#include <new>
#include <sstream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/option_check.hpp"

namespace frac::analysis {

const EstimatorResult& FitReport::primary_result() const {
  const auto* e = find(primary);
  if (!e) throw RuntimeError("powerlaw fit report has no primary estimator");
  return *e;
}

const EstimatorResult* FitReport::find(const std::string& name) const {
  for (const auto& e : mle)
    if (e.name == name) return &e;
  return nullptr;
}

void check_fit_options(const FitOptions& opt) {
  if (opt.model != "auto" && opt.model != "continuous" && opt.model != "discrete")
    throw UsageError("--model: expected auto, continuous or discrete, got '" + opt.model + "'");
  // Resamples beyond a million would run for days; p-values are good to 0.01 with 2500.
  if (opt.bootstrap < 0 || opt.bootstrap > 1000000)
    throw UsageError("--bootstrap: must lie in [0, 1000000], got " + std::to_string(opt.bootstrap));
  if (opt.gof_samples < 0 || opt.gof_samples > 1000000)
    throw UsageError("--gof-samples: must lie in [0, 1000000], got " + std::to_string(opt.gof_samples));
  if (opt.scan.min_tail < 2) throw UsageError("--min-tail: must be >= 2");
  check_in(opt.significance, "--significance", Interval::open(0, 1));
  check_in(opt.bins_per_decade, "--bins-per-decade", Interval::open_closed(0, 1000));
  cli::check_threads(opt.threads > 1u << 30 ? -1 : static_cast<int>(opt.threads), "--threads");
  if (!(opt.cell_mass >= 0) || !std::isfinite(opt.cell_mass)) throw UsageError("--cell-mass: must be >= 0");
  if (!(opt.scan.xmax > 0)) throw UsageError("--xmax: must be > 0");
  if (!std::isnan(opt.scan.xmin) && !(opt.scan.xmin > 0 && std::isfinite(opt.scan.xmin)))
    throw UsageError("--xmin: must be a positive number");
  if (std::isfinite(opt.scan.xmin) && !(opt.scan.xmin < opt.scan.xmax)) throw UsageError("--xmin must be below --xmax");
  // (logbin_min: NaN stands for the primary fit's x_min; logbin_max: infinity for no upper end)
  if (!std::isnan(opt.logbin_min) && !(opt.logbin_min >= 0 && std::isfinite(opt.logbin_min)))
    throw UsageError("--logbin-min: must be xmin, all or a number >= 0, got " + format_value(opt.logbin_min));
  if (!(opt.logbin_max > 0))
    throw UsageError("--logbin-max: must be inf or a positive number, got " + format_value(opt.logbin_max));
  if (!(opt.logbin_min < opt.logbin_max) && !std::isnan(opt.logbin_min))
    throw UsageError("--logbin-min must be below --logbin-max");
}

FitReport fit_powerlaw(std::span<const double> values, const FitOptions& opt, const std::string& what) try {
  check_fit_options(opt);

  validate_values(values, what);
  FitReport r;
  r.options = opt;
  std::vector<double> kept;
  kept.reserve(values.size());
  for (double v : values) {
    if (v > opt.scan.xmax)
      ++r.n_above_xmax;
    else
      kept.push_back(v);
  }
  if (r.n_above_xmax) {
    std::ostringstream w;
    w.precision(10);
    w << what << " below --xmax " << opt.scan.xmax;
    validate_values(kept, w.str());
  }
  r.n_values = static_cast<std::int64_t>(kept.size());
  r.integer_data = all_integers(kept);
  if (opt.model == "discrete" && !r.integer_data) {
    std::int64_t bad = 0;
    for (double v : kept) bad += v != std::floor(v);
    throw InputError(what + ": the discrete model needs integer values, but " + std::to_string(bad) + " of " +
                     std::to_string(kept.size()) + " values are not whole numbers");
  }
  const bool discrete_primary = opt.model == "discrete" || (opt.model == "auto" && r.integer_data);
  r.primary = discrete_primary ? "discrete_mle" : "continuous_mle";

  const Sample s = make_sample(kept);
  std::vector<Model> models{Model::continuous};
  if (r.integer_data) models.push_back(Model::discrete);
  for (Model m : models) {
    EstimatorResult e;
    e.model = m;
    e.name = std::string(model_name(m)) + "_mle";
    e.fit = fit_model(m, s, opt.scan);
    if (!e.fit.ok && e.name == r.primary)
      throw InputError(what + ": " + model_name(m) + " power-law fit failed: " + e.fit.failure);
    if (e.fit.ok) {
      e.bootstrap = bootstrap_uncertainty(m, s, opt.scan, opt.bootstrap, opt.seed, opt.threads);
      e.gof = gof_pvalue(m, s, e.fit, opt.scan, opt.gof_samples, opt.seed, opt.threads);
    }
    r.mle.push_back(std::move(e));
  }
  const EstimatorResult& primary = r.primary_result();
  if (opt.compare) r.comparisons = compare_alternatives(primary.model, s, primary.fit, opt.significance);

  r.histogram = log_histogram(kept, {opt.bins_per_decade, r.integer_data, opt.cell_mass});
  r.logbin_range.fit_min = std::isnan(opt.logbin_min) ? primary.fit.xmin : opt.logbin_min;
  r.logbin_range.fit_max = opt.logbin_max;
  r.logbin = fit_log_slope(r.histogram, r.logbin_range);
  return r;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the power-law fit of " + std::to_string(values.size()) + " values");
}

std::string summary_line(const FitReport& r) {
  const auto& p = r.primary_result();
  std::ostringstream o;
  o.precision(4);
  o << p.name << ": alpha = " << p.fit.alpha << " +- " << p.fit.alpha_stderr;
  if (p.bootstrap.samples) o << " (bootstrap " << p.bootstrap.alpha_std << ")";
  o << ", xmin = " << p.fit.xmin << ", n_tail = " << p.fit.n_tail << " of " << r.n_values;
  if (p.gof.samples) o << ", gof p = " << p.gof.p;
  if (r.logbin.ok) o << "; log-binned slope: alpha = " << -r.logbin.slope << " +- " << r.logbin.slope_stderr;
  if (r.n_above_xmax) o << "; " << r.n_above_xmax << " values above xmax left out";
  o << " (density exponent: beta of F(m) = alpha)";
  return o.str();
}

}  // namespace frac::analysis
