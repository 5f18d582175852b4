// powerlaw-fit: fits a power law to fragment masses (or cell counts, or any column of numbers) with every
// estimator side by side: continuous and discrete maximum likelihood with the KS choice of x_min (Clauset,
// Shalizi & Newman 2009), asymptotic and bootstrap errors, the bootstrap goodness-of-fit p-value,
// likelihood-ratio tests against exponential, lognormal and cutoff, and the log-binned least-squares slope.
// Method and output keys: docs/powerlaw-fit.md.
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

#include "analysis/fit_io.hpp"
#include "analysis/powerlaw.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/option_check.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

double parse_bound(const std::string& text, const std::string& option) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && !std::isnan(v)) return v;
  } catch (const std::logic_error&) {
  }
  throw UsageError(option + ": expected a number, got '" + text + "'");
}

// A bound of the log-binned slope fit: a value in the data's unit, or "<N>cells": N times the mean cell mass.
struct Bound {
  double value = 0;
  bool in_cells = false;
  double resolve(double cell_mass, const std::string& option) const {
    if (!in_cells) return value;
    if (!(cell_mass > 0)) throw UsageError(option + ": a bound in cells needs the mean cell mass (--cell-mass)");
    return value * cell_mass;
  }
};

Bound parse_bound_or_cells(const std::string& text, const std::string& option) {
  const std::string suffix = "cells";
  const bool cells = text.size() > suffix.size() && text.ends_with(suffix);
  return {parse_bound(cells ? text.substr(0, text.size() - suffix.size()) : text, option), cells};
}
// Every option's value, as parsed.
struct Options {
  cli::CommonOptions common;
  analysis::FitOptions opt;
  std::vector<std::string> inputs;
  std::string input_format = "auto", format = "hdf5", column = "mass", ks = "two-sided", histogram_csv;
  std::string xmin_text, xmax_text, logbin_min = "xmin", logbin_max = "inf";
  std::string min_cells_text = "file", cell_mass_text = "auto";
  bool no_compare = false;
  po::variables_map vm;
  // Resolved: the log-binned fit's bounds (maybe in cells) and whether the cell mass comes from the inputs.
  Bound lower, upper;
  bool cell_mass_auto = false;
};

cli::ToolSpec tool_spec() {
  return {"powerlaw-fit", "[options] INPUT|-",
          "Fits p(x) ~ x^-alpha for x >= xmin to fragment masses (a 'fragments' HDF5 file: /fragments/mass, or "
          "cell_count) or to a plain column of numbers (text, '#' comments allowed), and reports every estimator "
          "side by side: continuous_mle and, for integer data, discrete_mle (maximum likelihood, xmin by minimum "
          "KS distance, asymptotic error (alpha-1)/sqrt(n_tail), bootstrap error including xmin, goodness-of-fit "
          "p by the semi-parametric bootstrap; p <= 0.1 rejects the power law), likelihood-ratio tests of the "
          "primary fit against exponential, lognormal (Vuong) and power law with exponential cutoff (nested; "
          "'lr_<alt> R p': R > 0 favours the power law), and the weighted least-squares slope of the log-binned "
          "density histogram (biased; for comparison). alpha is the exponent of the DENSITY: for fragment masses "
          "F(m) ~ m^-beta, beta = alpha; the CCDF N(>m) falls as m^-(alpha-1). Values that are NaN, infinite, "
          "zero or negative, fewer than 10 values or fewer than 3 distinct ones are refused (exit 2). Output: the "
          "/fit group of an HDF5 file of kind 'fit', or with --format text 'key value' lines (unprefixed keys are "
          "the primary estimator; continuous_*, discrete_*, logbin_* the others; every key in docs/powerlaw-fit.md). "
          "With several inputs, both exponents are also fitted to each input alone (mean and standard error over "
          "inputs) and to the pool with each input left out (jackknife error). Fragment masses cluster near whole "
          "numbers of cells: the histogram's edges fall halfway between them (--cell-mass).",
          "  powerlaw-fit fragments.h5 -o fit.h5\n"
          "  powerlaw-fit fragments.h5 --column cell_count --min-cells 2 --format text\n"
          "  powerlaw-fit frag-s1.h5 frag-s2.h5 frag-s3.h5 --logbin-min 2cells --logbin-max 25cells --format text\n"
          "  fragment-count run.h5 | powerlaw-fit - --format text --bootstrap 500 --gof-samples 1000\n"
          "  powerlaw-fit values.txt --format text | awk '$1 == \"alpha\" {print $2}'"};
}

void parse_options(int argc, char** argv, Options& o) {
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&o.inputs)->required()->multitoken(),
                     "fragments files or text columns ('-' reads standard input); several are pooled into one sample "
                     "(e.g. the runs of several seeds)")(
      "input-format", po::value(&o.input_format)->default_value(o.input_format),
      "auto (HDF5 when the input starts with the HDF5 signature, else text), hdf5 or text")(
      "format", po::value(&o.format)->default_value(o.format),
      "output: hdf5 (the /fit group) or text (key value lines)")(
      "column", po::value(&o.column)->default_value(o.column),
      "fragments file: mass (continuous primary) or cell_count (integers: discrete primary)")(
      "min-cells", po::value(&o.min_cells_text)->default_value(o.min_cells_text),
      "fragments file: fit only fragments of at least N cells; 'file' takes the file's own min_cells "
      "attribute (fragment-count --min-cells; none: all fragments). The number left out is reported")(
      "model", po::value(&o.opt.model)->default_value(o.opt.model),
      "primary estimator: auto (discrete for integer data), continuous or discrete")(
      "xmin", po::value(&o.xmin_text), "fix the lower cutoff instead of scanning for it")(
      "xmax", po::value(&o.xmax_text),
      "upper cutoff: values above it are left out (and counted) and the power law is truncated there")(
      "min-tail", po::value(&o.opt.scan.min_tail)->default_value(o.opt.scan.min_tail),
      "xmin candidates must leave at least N values in the tail")(
      "ks", po::value(&o.ks)->default_value(o.ks),
      "KS distance of continuous fits: two-sided (sup|S-P|, CSN) or powerlaw-r (as R poweRlaw)")(
      "bootstrap", po::value(&o.opt.bootstrap)->default_value(o.opt.bootstrap),
      "non-parametric bootstrap resamples for the uncertainty of alpha and xmin (0: none)")(
      "gof-samples", po::value(&o.opt.gof_samples)->default_value(o.opt.gof_samples),
      "synthetic sets for the goodness-of-fit p-value (0: none; 2500 gives p to +-0.01)")(
      "no-compare", po::bool_switch(&o.no_compare), "skip the likelihood-ratio tests")(
      "significance", po::value(&o.opt.significance)->default_value(o.opt.significance, "0.1"),
      "p below this makes a likelihood-ratio test decisive ('favours')")(
      "bins-per-decade", po::value(&o.opt.bins_per_decade)->default_value(o.opt.bins_per_decade),
      "log-binned histogram: bins per decade")(
      "cell-mass", po::value(&o.cell_mass_text)->default_value(o.cell_mass_text),
      "mean cell mass: the histogram's edges fall halfway between the masses of fragments of k and k + 1 "
      "cells. auto: total mass / cells of the fragments files (none for text input); 0: plain log bins; "
      "or a value (cell counts always use 1)")(
      "logbin-min", po::value(&o.logbin_min)->default_value(o.logbin_min),
      "lower end of the log-binned slope fit: xmin (the primary fit's), all, a value, or N cells ('2cells')")(
      "logbin-max", po::value(&o.logbin_max)->default_value(o.logbin_max),
      "upper end of the log-binned slope fit: inf, a value, or N cells ('25cells')")(
      "threads", po::value(&o.opt.threads)->default_value(0),
      "threads for the resampling (0: all cores; results do not depend on it)")(
      "histogram-csv", po::value(&o.histogram_csv),
      "also write the log-binned density histogram as CSV (center,density,count,lower,upper) to this file");
  cli::add_common(desc, o.common, cli::kOutput | cli::kSeed | cli::kQuiet | cli::kConfig, cli::kOutputHdf5OrText);
  po::positional_options_description positional;
  positional.add("input", -1);
  o.vm = cli::parse(argc, argv, tool_spec(), desc, positional);
}

// Checks the options (before any input is read) and resolves them into the fit's options.
void resolve_options(Options& o) {
  if (o.input_format != "auto" && o.input_format != "hdf5" && o.input_format != "text")
    throw UsageError("--input-format: expected auto, hdf5 or text, got '" + o.input_format + "'");
  check_one_of(o.format, {"hdf5", "text"}, "--format");
  analysis::check_fit_options(o.opt);  // before any input is read
  std::vector<FileRole> input_roles{{"--config", o.common.config}};
  for (const std::string& input : o.inputs) input_roles.push_back({"FILE", input});
  check_file_roles(input_roles, {{"-o", o.common.output}, {"--histogram-csv", o.histogram_csv}});
  if (o.ks == "two-sided")
    o.opt.scan.ks = analysis::KsConvention::two_sided;
  else if (o.ks == "powerlaw-r")
    o.opt.scan.ks = analysis::KsConvention::powerlaw_r;
  else
    throw UsageError("--ks: expected two-sided or powerlaw-r, got '" + o.ks + "'");
  if (o.vm.count("xmin")) {
    o.opt.scan.xmin = parse_bound(o.xmin_text, "--xmin");
    if (!(o.opt.scan.xmin > 0) || !std::isfinite(o.opt.scan.xmin))
      throw UsageError("--xmin: must be a positive number");
  }
  if (o.vm.count("xmax")) {
    o.opt.scan.xmax = parse_bound(o.xmax_text, "--xmax");
    if (!(o.opt.scan.xmax > 0)) throw UsageError("--xmax: must be a positive number");
  }
  const auto nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  o.lower = o.logbin_min == "xmin"  ? Bound{nan}
            : o.logbin_min == "all" ? Bound{0}
                                    : parse_bound_or_cells(o.logbin_min, "--logbin-min");
  o.upper = o.logbin_max == "inf" ? Bound{inf} : parse_bound_or_cells(o.logbin_max, "--logbin-max");
  o.cell_mass_auto = o.cell_mass_text == "auto";
  if (!o.cell_mass_auto) o.opt.cell_mass = parse_bound(o.cell_mass_text, "--cell-mass");
  o.opt.compare = !o.no_compare;
  o.opt.seed = o.common.seed;
}

// --min-cells of a fragments file: its own min_cells attribute ('file'), or a whole number.
std::int64_t min_cells_of(const std::string& text, const io::Group& root) {
  if (text == "file") return analysis::fragments_min_cells(root);
  const double v = parse_bound(text, "--min-cells");
  if (!(v >= 0) || v != std::floor(v)) throw UsageError("--min-cells: expected 'file' or a whole number >= 0");
  return static_cast<std::int64_t>(v);
}

int run(int argc, char** argv) {
  Options o;
  parse_options(argc, argv, o);
  resolve_options(o);
  ToolRun run = start_run("powerlaw-fit", cli::command_line(argc, argv));
  run.parameters = cli::resolved_options(o.vm);
  run.seed = std::to_string(o.common.seed);

  // Input: fragments files, or columns of numbers; several are pooled.
  analysis::InputOptions in;
  in.format = o.input_format;
  in.column = o.column;
  in.fragments_options_given = !o.vm["column"].defaulted() || !o.vm["min-cells"].defaulted();
  in.min_cells = [&](const io::Group& root) { return min_cells_of(o.min_cells_text, root); };
  const analysis::FitInput values = analysis::read_pooled_inputs(o.inputs, in, run);

  analysis::FitOptions& opt = o.opt;
  if (o.cell_mass_auto) opt.cell_mass = values.column == "mass" ? values.mean_cell_mass() : 0.0;
  const double cells_unit = values.column == "cell_count" ? 1.0 : opt.cell_mass;
  opt.logbin_min = o.lower.resolve(cells_unit, "--logbin-min");
  opt.logbin_max = o.upper.resolve(cells_unit, "--logbin-max");
  auto report = analysis::fit_powerlaw(values.values, opt, values.source);
  report.spread = analysis::input_spread(values.values, values.input_sizes, report);

  if (!o.histogram_csv.empty()) {
    std::ostringstream csv;
    analysis::write_histogram_csv(csv, report, provenance_line(run));
    io::write_file_atomically(o.histogram_csv, csv.str());
  }
  analysis::write_fit_file(o.common.output, report, values, run, o.format == "text");
  if (!o.common.quiet) {
    std::cerr << "powerlaw-fit: " << analysis::summary_line(report) << "\n";
    if (values.n_excluded_min_cells)
      std::cerr << "powerlaw-fit: left out " << values.n_excluded_min_cells << " of " << values.n_read
                << " fragments below " << values.min_cells << " cells\n";
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("powerlaw-fit", [&] { return run(argc, argv); });
}
