#include "analysis/fit_io.hpp"

#include "io/atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>

#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/provenance_text.hpp"

namespace frac::analysis {
// (The file formats are written with io's HDF5 and file layer throughout.)
using namespace frac::io;

using analysis::FitReport;

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

std::string fmt(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::int64_t as_int(bool b) { return b ? 1 : 0; }

// The two estimators of an InputSpread with their HDF5 group names.
template <class Spread>
auto spread_parts(Spread& s) {
  return std::array{std::pair{"mle", &s.mle}, std::pair{"log_binned_slope", &s.logbin}};
}

const char* ks_name(analysis::KsConvention k) {
  return k == analysis::KsConvention::two_sided ? "two_sided" : "powerlaw_r";
}

}  // namespace

std::vector<double> read_number_column(std::istream& in, const std::string& name, std::size_t max_values) {
  constexpr std::size_t kMaxLine = 4096;
  constexpr std::int64_t kMaxBadLines = 1000;
  std::vector<double> out;
  std::string line, first_bad;
  std::int64_t lineno = 0, bad = 0, first_bad_line = 0;
  std::vector<char> buffer(kMaxLine + 1);
  while (bad < kMaxBadLines) {
    in.getline(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0 && in.eof()) break;
    ++lineno;
    if (in.fail() && !in.eof())
      throw InputError(name + ": line " + std::to_string(lineno) + " is longer than " + std::to_string(kMaxLine) +
                       " characters: not a column of numbers");
    line.assign(buffer.data(), in.eof() ? got : got - 1);
    if (line.find('\0') != std::string::npos)
      throw InputError(name + ": line " + std::to_string(lineno) + " holds a NUL byte: not a column of numbers");
    const auto hash = line.find('#');
    const std::string text = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (text.empty()) continue;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') {
      if (bad++ == 0) first_bad_line = lineno, first_bad = text;
      continue;
    }
    if (out.size() >= max_values)
      throw InputError(name + ": more than " + std::to_string(max_values) + " values (at most that many are read)");
    out.push_back(v);
    if (in.eof()) break;
  }
  if (in.bad()) throw InputError(name + ": read error");
  if (bad)
    throw InputError(name + ": " + (bad == kMaxBadLines ? "at least " : "") + std::to_string(bad) + " line" +
                     (bad == 1 ? " is" : "s are") + " not a single number (first: line " +
                     std::to_string(first_bad_line) + ": '" + first_bad.substr(0, 60) + "')");
  return out;
}

FitInput read_text_values(const std::string& path) {
  FitInput in;
  in.source = path;
  if (path == "-") {
    in.values = read_number_column(std::cin, "-");
    if (in.values.empty()) throw InputError("-: standard input holds no values");
  } else {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory");
    std::ifstream f(path);
    if (!f) throw InputError(path + ": cannot read");
    in.values = read_number_column(f, path);
    if (in.values.empty()) throw InputError(path + ": holds no values");
  }
  in.n_read = static_cast<std::int64_t>(in.values.size());
  return in;
}

FitInput read_fragment_values(const Group& root, const std::string& column, std::int64_t min_cells) {
  if (column != "mass" && column != "cell_count")
    throw UsageError("--column: expected mass or cell_count, got '" + column + "'");
  check_header(root, {"fragments"});
  if (!root.has("fragments")) throw InputError(root.file() + ": holds no /fragments group");
  const Group g = root.group("fragments");
  FitInput in;
  in.column = column;
  in.source = g.where(column);
  if (column == "mass") {
    in.values = g.read<double>("mass", nullptr, 1);
    in.unit = g.has_attr("unit", "mass") ? g.attr_string("unit", "mass") : "kg";
  } else {
    const auto cells = g.read<std::int64_t>("cell_count", nullptr, 1);
    in.values.assign(cells.begin(), cells.end());
    in.unit = "1";
  }
  in.n_read = static_cast<std::int64_t>(in.values.size());
  if (g.has_attr("min_cells")) in.fragments_min_cells = g.attr_int("min_cells");
  const auto cells = g.read<std::int64_t>("cell_count", nullptr, 1);
  in.cells = std::accumulate(cells.begin(), cells.end(), std::int64_t{0});
  if (g.has_attr("total_mass")) in.total_mass = g.attr_double("total_mass");
  if (min_cells > 0) {
    in.min_cells = min_cells;
    if (cells.size() != in.values.size())
      throw InputError(g.where("cell_count") + ": " + std::to_string(cells.size()) + " entries, but " + column +
                       " has " + std::to_string(in.values.size()));
    std::vector<double> kept;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (cells[i] >= min_cells)
        kept.push_back(in.values[i]);
      else
        ++in.n_excluded_min_cells;
    }
    in.values = std::move(kept);
  }
  return in;
}

std::int64_t fragments_min_cells(const Group& root) {
  check_header(root, {"fragments"});
  if (!root.has("fragments")) throw InputError(root.file() + ": holds no /fragments group");
  const Group g = root.group("fragments");
  return g.has_attr("min_cells") ? std::max<std::int64_t>(0, g.attr_int("min_cells")) : 0;
}

bool input_is_hdf5(const std::string& path) {
  if (path == "-") {
    const int c = std::getc(stdin);
    if (c == EOF) throw InputError("-: standard input is empty");
    std::ungetc(c, stdin);
    return c == 0x89;  // first byte of the HDF5 signature "\211HDF\r\n\032\n"
  }
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory");
  silence_hdf5_errors();
  return H5Fis_hdf5(path.c_str()) > 0;
}

namespace {

// The /fit group's own attributes: what alpha means, the input and the options.
void write_fit_attributes(Group& fit, const FitReport& r, const FitInput& input) {
  const auto& opt = r.options;
  fit.set_attr("exponent_convention",
               "alpha is the exponent of the probability density p(x) ~ x^-alpha for x >= xmin; for a fragment "
               "mass distribution F(m) ~ m^-beta (fragments per unit mass), beta = alpha; the CCDF N(>m) and "
               "counts per logarithmic bin fall as m^-(alpha-1)");
  fit.set_attr("primary", r.primary);
  fit.set_attr("source", input.source);
  fit.set_attr("column", input.column);
  fit.set_attr("unit", input.unit);
  fit.set_attr("n_read", input.n_read);
  fit.set_attr("n_excluded_min_cells", input.n_excluded_min_cells);
  fit.set_attr("min_cells", input.min_cells);
  fit.set_attr("fragments_min_cells", input.fragments_min_cells);
  fit.set_attr("n_above_xmax", r.n_above_xmax);
  fit.set_attr("n_values", r.n_values);
  fit.set_attr("integer_data", as_int(r.integer_data));
  fit.set_attr("model_option", opt.model);
  fit.set_attr("xmax", opt.scan.xmax);
  fit.set_attr("xmin_fixed", opt.scan.xmin);
  fit.set_attr("min_tail", opt.scan.min_tail);
  fit.set_attr("ks_convention", ks_name(opt.scan.ks));
  fit.set_attr("significance", opt.significance);
  fit.set_attr("seed", static_cast<std::int64_t>(opt.seed));
}

// /fit/<estimator>: the fit, its bootstrap and goodness-of-fit numbers and samples.
void write_estimator(Group& fit, const analysis::EstimatorResult& e, const std::string& unit) {
  Group g = fit.create_group(e.name);
  const auto& f = e.fit;
  g.set_attr("model", analysis::model_name(e.model));
  g.set_attr("ok", as_int(f.ok));
  g.set_attr("failure", f.failure);
  g.set_attr("alpha", f.alpha);
  g.set_attr("alpha_stderr", f.alpha_stderr);
  g.set_attr("xmin", f.xmin);
  g.set_attr("xmax", f.xmax);
  g.set_attr("xmin_unit", unit);
  g.set_attr("n_tail", f.n_tail);
  g.set_attr("ks_distance", f.ks);
  g.set_attr("loglik", f.loglik);
  g.set_attr("xmin_candidates", f.candidates);
  g.set_attr("bootstrap_samples", static_cast<std::int64_t>(e.bootstrap.samples));
  g.set_attr("bootstrap_failed", static_cast<std::int64_t>(e.bootstrap.failed));
  g.set_attr("alpha_bootstrap_std", e.bootstrap.alpha_std);
  g.set_attr("alpha_bootstrap_mean", e.bootstrap.alpha_mean);
  g.set_attr("xmin_bootstrap_std", e.bootstrap.xmin_std);
  g.set_attr("xmin_bootstrap_mean", e.bootstrap.xmin_mean);
  g.set_attr("n_tail_bootstrap_mean", e.bootstrap.n_tail_mean);
  g.set_attr("gof_samples", static_cast<std::int64_t>(e.gof.samples));
  g.set_attr("gof_failed", static_cast<std::int64_t>(e.gof.failed));
  g.set_attr("gof_p", e.gof.p);
  const auto B = static_cast<hsize_t>(e.bootstrap.alpha.size());
  g.write("bootstrap_alpha", std::span<const double>(e.bootstrap.alpha), {B}, "1");
  g.write("bootstrap_xmin", std::span<const double>(e.bootstrap.xmin), {B}, unit);
  g.write("bootstrap_n_tail", std::span<const std::int64_t>(e.bootstrap.n_tail), {B}, "1");
  g.write("gof_ks_distance", std::span<const double>(e.gof.ks), {static_cast<hsize_t>(e.gof.ks.size())}, "1");
}

// /fit/comparison/<alternative>: one likelihood-ratio test of the primary fit.
void write_comparison(Group& fit, const analysis::Comparison& c, const std::string& primary) {
  Group g = fit.create_group("comparison/" + c.alternative);
  g.set_attr("estimator", primary);
  g.set_attr("ok", as_int(c.ok));
  g.set_attr("failure", c.failure);
  g.set_attr("nested", as_int(c.nested));
  g.set_attr("test", c.nested ? "likelihood ratio, 2R ~ chi2_1 (one-sided)" : "Vuong, two-sided");
  g.set_attr("R", c.R);
  g.set_attr("z", c.z);
  g.set_attr("p", c.p);
  g.set_attr("favours", c.favours);
  g.set_attr("loglik_powerlaw", c.loglik_powerlaw);
  g.set_attr("loglik_alternative", c.loglik_alternative);
  g.set_attr("param_names", c.param_names);
  g.set_attr("params", c.params);
}

// /fit/histogram: the log-binned density histogram and which bins the slope fit used.
void write_histogram(Group& fit, const FitReport& r, const std::string& unit) {
  const auto& h = r.histogram;
  Group hg = fit.create_group("histogram");
  hg.set_attr("bins_per_decade", h.bins_per_decade);
  hg.set_attr("integer_data", as_int(h.integer_data));
  hg.set_attr("cell_mass", h.cluster_unit);
  hg.set_attr("n_total", h.n_total);
  hg.set_attr("density_definition", "count / (n_total * width): per unit of x, normalised to 1 over all values");
  const auto K = static_cast<hsize_t>(h.size());
  const std::string inv_unit = unit.empty() || unit == "1" ? unit : "1/" + unit;
  hg.write("edges", std::span<const double>(h.edges), {K + 1}, unit);
  hg.write("count", std::span<const std::int64_t>(h.count), {K}, "1");
  hg.write("width", std::span<const double>(h.width), {K}, unit);
  hg.write("center", std::span<const double>(h.center), {K}, unit);
  hg.write("density", std::span<const double>(h.density), {K}, inv_unit);
  hg.write("used_in_fit", std::span<const std::uint8_t>(r.logbin.used), {K}, "1");
}

// /fit/log_binned_slope: the least-squares slope of the histogram.
void write_log_binned_slope(Group& fit, const FitReport& r) {
  const auto& l = r.logbin;
  Group lg = fit.create_group("log_binned_slope");
  lg.set_attr("ok", as_int(l.ok));
  lg.set_attr("alpha", -l.slope);
  lg.set_attr("alpha_stderr", l.slope_stderr);
  lg.set_attr("slope", l.slope);
  lg.set_attr("slope_stderr", l.slope_stderr);
  lg.set_attr("intercept", l.intercept);
  lg.set_attr("intercept_stderr", l.intercept_stderr);
  lg.set_attr("chi2_per_dof", l.chi2_per_dof);
  lg.set_attr("n_bins", static_cast<std::int64_t>(l.n_bins));
  lg.set_attr("fit_min", l.fit_min);
  lg.set_attr("fit_max", l.fit_max);
  lg.set_attr("bins_per_decade", r.histogram.bins_per_decade);
  lg.set_attr("range_min", r.logbin_range.fit_min);
  lg.set_attr("range_max", r.logbin_range.fit_max);
  lg.set_attr("method", "weighted least squares of ln(density) on ln(center), weights = counts; see /fit/histogram");
}

// /fit/input_spread: both exponents per input and left-one-out (several inputs only).
void write_input_spread(Group& fit, const FitReport& r) {
  Group sg = fit.create_group("input_spread");
  sg.set_attr("inputs", static_cast<std::int64_t>(r.spread.inputs));
  for (const auto& [name, e] : spread_parts(r.spread)) {
    Group g = sg.create_group(name);
    g.set_attr("n_ok", static_cast<std::int64_t>(e->n_ok));
    g.set_attr("mean", e->mean);
    g.set_attr("stderr_mean", e->stderr_mean);
    g.set_attr("jackknife_stderr", e->jackknife_stderr);
    const auto n = static_cast<hsize_t>(e->per_input.size());
    g.write("alpha_per_input", std::span<const double>(e->per_input), {n}, "1");
    g.write("alpha_leave_one_out", std::span<const double>(e->leave_one_out), {n}, "1");
  }
}

analysis::EstimatorResult read_estimator(const Group& fit, const char* name) {
  const Group g = fit.group(name);
  analysis::EstimatorResult e;
  e.name = name;
  e.model = g.attr_string("model") == "discrete" ? analysis::Model::discrete : analysis::Model::continuous;
  e.fit.ok = g.attr_int("ok") != 0;
  e.fit.failure = g.attr_string("failure");
  e.fit.alpha = g.attr_double("alpha");
  e.fit.alpha_stderr = g.attr_double("alpha_stderr");
  e.fit.xmin = g.attr_double("xmin");
  e.fit.xmax = g.attr_double("xmax");
  e.fit.n_tail = g.attr_int("n_tail");
  e.fit.ks = g.attr_double("ks_distance");
  e.fit.loglik = g.attr_double("loglik");
  e.fit.candidates = g.attr_int("xmin_candidates");
  e.bootstrap.samples = static_cast<int>(g.attr_int("bootstrap_samples"));
  e.bootstrap.failed = static_cast<int>(g.attr_int("bootstrap_failed"));
  e.bootstrap.alpha_std = g.attr_double("alpha_bootstrap_std");
  e.bootstrap.alpha_mean = g.attr_double("alpha_bootstrap_mean");
  e.bootstrap.xmin_std = g.attr_double("xmin_bootstrap_std");
  e.bootstrap.xmin_mean = g.attr_double("xmin_bootstrap_mean");
  e.bootstrap.n_tail_mean = g.attr_double("n_tail_bootstrap_mean");
  e.bootstrap.alpha = g.read<double>("bootstrap_alpha");
  e.bootstrap.xmin = g.read<double>("bootstrap_xmin");
  e.bootstrap.n_tail = g.read<std::int64_t>("bootstrap_n_tail");
  e.gof.samples = static_cast<int>(g.attr_int("gof_samples"));
  e.gof.failed = static_cast<int>(g.attr_int("gof_failed"));
  e.gof.p = g.attr_double("gof_p");
  e.gof.ks = g.read<double>("gof_ks_distance");
  return e;
}

analysis::Comparison read_comparison(const Group& g, const char* alt) {
  analysis::Comparison c;
  c.alternative = alt;
  c.ok = g.attr_int("ok") != 0;
  c.failure = g.attr_string("failure");
  c.nested = g.attr_int("nested") != 0;
  c.R = g.attr_double("R");
  c.z = g.attr_double("z");
  c.p = g.attr_double("p");
  c.favours = g.attr_string("favours");
  c.loglik_powerlaw = g.attr_double("loglik_powerlaw");
  c.loglik_alternative = g.attr_double("loglik_alternative");
  c.params = g.attr_doubles("params");
  return c;
}

// /fit/histogram and /fit/log_binned_slope.
void read_histogram_and_slope(const Group& fit, FitReport& r) {
  const Group hg = fit.group("histogram");
  r.histogram.bins_per_decade = hg.attr_double("bins_per_decade");
  r.histogram.integer_data = hg.attr_int("integer_data") != 0;
  r.histogram.cluster_unit = hg.attr_double("cell_mass");
  r.histogram.n_total = hg.attr_int("n_total");
  r.histogram.edges = hg.read<double>("edges", nullptr, 1);
  r.histogram.count = hg.read<std::int64_t>("count", nullptr, 1);
  r.histogram.width = hg.read<double>("width", nullptr, 1);
  r.histogram.center = hg.read<double>("center", nullptr, 1);
  r.histogram.density = hg.read<double>("density", nullptr, 1);
  r.logbin.used = hg.read<std::uint8_t>("used_in_fit", nullptr, 1);
  const Group lg = fit.group("log_binned_slope");
  r.logbin.ok = lg.attr_int("ok") != 0;
  r.logbin.slope = lg.attr_double("slope");
  r.logbin.slope_stderr = lg.attr_double("slope_stderr");
  r.logbin.intercept = lg.attr_double("intercept");
  r.logbin.intercept_stderr = lg.attr_double("intercept_stderr");
  r.logbin.chi2_per_dof = lg.attr_double("chi2_per_dof");
  r.logbin.n_bins = static_cast<int>(lg.attr_int("n_bins"));
  r.logbin.fit_min = lg.attr_double("fit_min");
  r.logbin.fit_max = lg.attr_double("fit_max");
  r.logbin_range.fit_min = lg.attr_double("range_min");
  r.logbin_range.fit_max = lg.attr_double("range_max");
}

void read_input_spread(const Group& sg, FitReport& r) {
  r.spread.inputs = static_cast<int>(sg.attr_int("inputs"));
  for (const auto& [name, e] : spread_parts(r.spread)) {
    const Group g = sg.group(name);
    e->n_ok = static_cast<int>(g.attr_int("n_ok"));
    e->mean = g.attr_double("mean");
    e->stderr_mean = g.attr_double("stderr_mean");
    e->jackknife_stderr = g.attr_double("jackknife_stderr");
    e->per_input = g.read<double>("alpha_per_input");
    e->leave_one_out = g.read<double>("alpha_leave_one_out");
  }
}

// "key value" lines on a stream, numbers as fmt writes them.
struct KeyValues {
  std::ostream& out;
  void text(const std::string& key, const std::string& value) const { out << key << ' ' << value << '\n'; }
  void number(const std::string& key, double v) const { text(key, fmt(v)); }
  void integer(const std::string& key, std::int64_t v) const { text(key, std::to_string(v)); }
};

// One estimator's keys, prefixed ("" for the primary, which also gets beta); its failure when it failed.
void estimator_text(const KeyValues& kv, const analysis::EstimatorResult& e, const std::string& prefix) {
  const auto& f = e.fit;
  if (!f.ok) {
    kv.text(prefix + "failure", "'" + f.failure + "'");
    return;
  }
  kv.number(prefix + "alpha", f.alpha);
  if (prefix.empty()) kv.number("beta", f.alpha);
  kv.number(prefix + "alpha_stderr", f.alpha_stderr);
  kv.number(prefix + "alpha_bootstrap_std", e.bootstrap.alpha_std);
  kv.number(prefix + "alpha_bootstrap_mean", e.bootstrap.alpha_mean);
  kv.number(prefix + "xmin", f.xmin);
  kv.number(prefix + "xmin_bootstrap_std", e.bootstrap.xmin_std);
  kv.number(prefix + "xmax", f.xmax);
  kv.integer(prefix + "n_tail", f.n_tail);
  kv.number(prefix + "n_tail_bootstrap_mean", e.bootstrap.n_tail_mean);
  kv.number(prefix + "ks_distance", f.ks);
  kv.number(prefix + "loglik", f.loglik);
  kv.integer(prefix + "xmin_candidates", f.candidates);
  kv.number(prefix + "gof_p", e.gof.p);
  kv.integer(prefix + "gof_samples", e.gof.samples);
  kv.integer(prefix + "gof_failed", e.gof.failed);
  kv.integer(prefix + "bootstrap_samples", e.bootstrap.samples);
  kv.integer(prefix + "bootstrap_failed", e.bootstrap.failed);
}

void comparisons_text(const KeyValues& kv, const FitReport& r) {
  for (const auto& c : r.comparisons) {
    const std::string k = "lr_" + c.alternative;
    if (!c.ok) {
      kv.text(k + "_failure", "'" + c.failure + "'");
      continue;
    }
    kv.text(k, fmt(c.R) + " " + fmt(c.p));
    kv.number(k + "_z", c.z);
    kv.text(k + "_favours", c.favours);
    for (std::size_t i = 0; i < c.params.size() && i < c.param_names.size(); ++i)
      kv.number(k + "_" + c.param_names[i], c.params[i]);
  }
}

void log_binned_slope_text(const KeyValues& kv, const FitReport& r) {
  const auto& l = r.logbin;
  kv.integer("logbin_ok", as_int(l.ok));
  kv.number("logbin_alpha", -l.slope);
  kv.number("logbin_alpha_stderr", l.slope_stderr);
  kv.number("logbin_slope", l.slope);
  kv.number("logbin_intercept", l.intercept);
  kv.number("logbin_chi2_per_dof", l.chi2_per_dof);
  kv.integer("logbin_bins", l.n_bins);
  kv.number("logbin_fit_min", l.fit_min);
  kv.number("logbin_fit_max", l.fit_max);
  kv.number("logbin_bins_per_decade", r.histogram.bins_per_decade);
  kv.number("logbin_cell_mass", r.histogram.cluster_unit);
  kv.number("logbin_range_min", r.logbin_range.fit_min);
  kv.number("logbin_range_max", r.logbin_range.fit_max);
}

void input_spread_text(const KeyValues& kv, const FitReport& r) {
  kv.integer("inputs", r.spread.inputs);
  for (const auto& [name, e] : spread_parts(r.spread)) {
    const std::string k = std::string(name) == "mle" ? "alpha" : "logbin_alpha";
    std::string list;
    for (double v : e->per_input) list += (list.empty() ? "" : " ") + fmt(v);
    kv.text(k + "_inputs", list);
    kv.number(k + "_input_mean", e->mean);
    kv.number(k + "_input_stderr", e->stderr_mean);
    kv.number(k + "_jackknife_stderr", e->jackknife_stderr);
  }
}

}  // namespace

void write_fit(Group& root, const FitReport& r, const FitInput& input) {
  Group fit = root.create_group("fit");
  write_fit_attributes(fit, r, input);
  for (const auto& e : r.mle) write_estimator(fit, e, input.unit);
  for (const auto& c : r.comparisons) write_comparison(fit, c, r.primary);
  write_histogram(fit, r, input.unit);
  write_log_binned_slope(fit, r);
  if (r.spread.inputs > 0) write_input_spread(fit, r);
}

FitReport read_fit(const Group& root) {
  if (!root.has("fit")) throw InputError(root.file() + ": holds no /fit group");
  const Group fit = root.group("fit");
  FitReport r;
  r.primary = fit.attr_string("primary");
  r.n_values = fit.attr_int("n_values");
  r.n_above_xmax = fit.attr_int("n_above_xmax");
  r.integer_data = fit.attr_int("integer_data") != 0;
  r.options.seed = static_cast<std::uint64_t>(fit.attr_int("seed"));
  r.options.scan.xmax = fit.attr_double("xmax");
  r.options.scan.xmin = fit.attr_double("xmin_fixed");
  r.options.scan.min_tail = fit.attr_int("min_tail");
  for (const char* name : {"continuous_mle", "discrete_mle"})
    if (fit.has(name)) r.mle.push_back(read_estimator(fit, name));
  if (fit.has("comparison")) {
    for (const char* alt : {"exponential", "lognormal", "cutoff"}) {
      const std::string path = std::string("comparison/") + alt;
      if (fit.has(path)) r.comparisons.push_back(read_comparison(fit.group(path), alt));
    }
  }
  read_histogram_and_slope(fit, r);
  if (fit.has("input_spread")) read_input_spread(fit.group("input_spread"), r);
  return r;
}

void write_fit_text(std::ostream& out, const FitReport& r, const FitInput& input, const std::string& provenance) {
  const KeyValues kv{out};
  out << csv_comment(provenance)
      << "# alpha: exponent of the probability density p(x) ~ x^-alpha, x >= xmin. For fragment masses\n"
      << "# F(m) ~ m^-beta (fragments per unit mass): beta = alpha. The CCDF N(>m) and the counts per\n"
      << "# logarithmic bin fall as m^-(alpha-1). Unprefixed keys: the primary estimator. Keys: docs/powerlaw-fit.md\n";
  kv.text("source", input.source.empty() ? "-" : input.source);
  kv.text("column", input.column.empty() ? "-" : input.column);
  kv.text("unit", input.unit.empty() ? "-" : input.unit);
  kv.integer("n_read", input.n_read);
  kv.integer("n_excluded_min_cells", input.n_excluded_min_cells);
  kv.integer("n_above_xmax", r.n_above_xmax);
  kv.integer("n_values", r.n_values);
  kv.integer("integer_data", as_int(r.integer_data));
  kv.text("primary", r.primary);
  kv.integer("seed", static_cast<std::int64_t>(r.options.seed));
  estimator_text(kv, r.primary_result(), "");
  comparisons_text(kv, r);
  for (const auto& e : r.mle) estimator_text(kv, e, std::string(analysis::model_name(e.model)) + "_");
  log_binned_slope_text(kv, r);
  if (r.spread.inputs == 0) return;
  input_spread_text(kv, r);
}

DistinctInputs::DistinctInputs(const std::vector<std::string>& paths) : paths_(paths) {
  for (std::size_t b = 1; b < paths_.size(); ++b)
    for (std::size_t a = 0; a < b; ++a)
      if (same_file(paths_[a], paths_[b]))
        throw UsageError("inputs '" + paths_[a] + "' and '" + paths_[b] +
                         "' are one file: pooled twice, its values would count twice");
}

void DistinctInputs::add(std::size_t k, const io::Group& root) {
  const std::string uuid = io::read_provenance(root).file_uuid;
  if (uuid.empty()) return;
  for (const auto& [seen, a] : uuids_)
    if (seen == uuid)
      throw UsageError("inputs '" + paths_[a] + "' and '" + paths_.at(k) + "' are copies of one file (the same " +
                       "/provenance file_uuid " + uuid + "): pooled twice, its values would count twice");
  uuids_.emplace_back(uuid, k);
}

void pool_into(FitInput& pooled, const FitInput& one) {
  if (pooled.source.empty()) {
    pooled = one;
    pooled.input_sizes = {one.values.size()};
    return;
  }
  if (pooled.unit != one.unit || pooled.column != one.column)
    throw InputError(one.source + ": cannot pool " + (one.column.empty() ? "text" : one.column) + " values with " +
                     (pooled.column.empty() ? "text" : pooled.column) + " values of " + pooled.source);
  pooled.values.insert(pooled.values.end(), one.values.begin(), one.values.end());
  pooled.source += " + " + one.source;
  pooled.n_read += one.n_read;
  pooled.n_excluded_min_cells += one.n_excluded_min_cells;
  pooled.total_mass += one.total_mass;
  pooled.cells += one.cells;
  pooled.input_sizes.push_back(one.values.size());
  pooled.min_cells = std::max(pooled.min_cells, one.min_cells);
  if (pooled.fragments_min_cells != one.fragments_min_cells) pooled.fragments_min_cells = -1;
}

void write_histogram_csv(std::ostream& out, const analysis::FitReport& report, const std::string& provenance) {
  const auto& h = report.histogram;
  out << csv_comment(provenance) << "center,density,count,lower,upper\n";
  out.precision(10);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h.count[k] > 0)
      out << h.center[k] << "," << h.density[k] << "," << h.count[k] << "," << h.edges[k] << "," << h.edges[k + 1]
          << "\n";
}

FitInput read_pooled_inputs(const std::vector<std::string>& inputs, const InputOptions& options, ToolRun& run) {
  FitInput values;
  DistinctInputs distinct(inputs);
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const std::string& input = inputs[k];
    const bool hdf5 = options.format == "hdf5" || (options.format == "auto" && input_is_hdf5(input));
    FitInput one;
    if (hdf5) {
      const io::Group root = io::open_input(input);
      const std::int64_t min_cells = options.min_cells(root);
      distinct.add(k, root);
      one = read_fragment_values(root, options.column, min_cells);
      io::add_input(run, root);
    } else {
      if (options.fragments_options_given)
        throw UsageError("--column and --min-cells apply to a fragments file, not to text input");
      one = read_text_values(input);
    }
    pool_into(values, one);
  }
  return values;
}

void write_fit_file(const std::string& path, const FitReport& report, const FitInput& input, const ToolRun& run,
                    bool text) {
  if (text) {
    std::ostringstream out;
    write_fit_text(out, report, input, provenance_line(run));
    write_file_atomically(path, out.str());
    return;
  }
  io::OutputFile out(path);
  io::write_header(out.root(), "fit", run, out.uuid());
  write_fit(out.root(), report, input);
  out.commit();
}

}  // namespace frac::analysis
