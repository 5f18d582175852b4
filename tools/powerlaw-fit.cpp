// powerlaw-fit: fits a power law to fragment masses (or cell counts, or any column of numbers) with every
// estimator side by side: continuous and discrete maximum likelihood with the KS choice of x_min (Clauset,
// Shalizi & Newman 2009), asymptotic and bootstrap errors, the bootstrap goodness-of-fit p-value,
// likelihood-ratio tests against exponential, lognormal and cutoff, and the log-binned least-squares slope.
// Method and output keys: docs/powerlaw-fit.md.
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

#include "analysis/powerlaw.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "analysis/fit_io.hpp"
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

int run(int argc, char** argv) {
  const cli::ToolSpec spec{
      "powerlaw-fit", "[options] INPUT|-",
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
  cli::CommonOptions common;
  analysis::FitOptions opt;
  std::vector<std::string> inputs;
  std::string input_format = "auto", format = "hdf5", column = "mass", ks = "two-sided", histogram_csv;
  std::string xmin_text, xmax_text, logbin_min = "xmin", logbin_max = "inf";
  std::string min_cells_text = "file", cell_mass_text = "auto";
  bool no_compare = false;
  po::options_description desc("Options");
  desc.add_options()
      ("input", po::value(&inputs)->required()->multitoken(),
       "fragments files or text columns ('-' reads standard input); several are pooled into one sample "
       "(e.g. the runs of several seeds)")
      ("input-format", po::value(&input_format)->default_value(input_format),
       "auto (HDF5 when the input starts with the HDF5 signature, else text), hdf5 or text")
      ("format", po::value(&format)->default_value(format), "output: hdf5 (the /fit group) or text (key value lines)")
      ("column", po::value(&column)->default_value(column),
       "fragments file: mass (continuous primary) or cell_count (integers: discrete primary)")
      ("min-cells", po::value(&min_cells_text)->default_value(min_cells_text),
       "fragments file: fit only fragments of at least N cells; 'file' takes the file's own min_cells "
       "attribute (fragment-count --min-cells; none: all fragments). The number left out is reported")
      ("model", po::value(&opt.model)->default_value(opt.model),
       "primary estimator: auto (discrete for integer data), continuous or discrete")
      ("xmin", po::value(&xmin_text), "fix the lower cutoff instead of scanning for it")
      ("xmax", po::value(&xmax_text),
       "upper cutoff: values above it are left out (and counted) and the power law is truncated there")
      ("min-tail", po::value(&opt.scan.min_tail)->default_value(opt.scan.min_tail),
       "xmin candidates must leave at least N values in the tail")
      ("ks", po::value(&ks)->default_value(ks),
       "KS distance of continuous fits: two-sided (sup|S-P|, CSN) or powerlaw-r (as R poweRlaw)")
      ("bootstrap", po::value(&opt.bootstrap)->default_value(opt.bootstrap),
       "non-parametric bootstrap resamples for the uncertainty of alpha and xmin (0: none)")
      ("gof-samples", po::value(&opt.gof_samples)->default_value(opt.gof_samples),
       "synthetic sets for the goodness-of-fit p-value (0: none; 2500 gives p to +-0.01)")
      ("no-compare", po::bool_switch(&no_compare), "skip the likelihood-ratio tests")
      ("significance", po::value(&opt.significance)->default_value(opt.significance, "0.1"),
       "p below this makes a likelihood-ratio test decisive ('favours')")
      ("bins-per-decade", po::value(&opt.bins_per_decade)->default_value(opt.bins_per_decade),
       "log-binned histogram: bins per decade")
      ("cell-mass", po::value(&cell_mass_text)->default_value(cell_mass_text),
       "mean cell mass: the histogram's edges fall halfway between the masses of fragments of k and k + 1 "
       "cells. auto: total mass / cells of the fragments files (none for text input); 0: plain log bins; "
       "or a value (cell counts always use 1)")
      ("logbin-min", po::value(&logbin_min)->default_value(logbin_min),
       "lower end of the log-binned slope fit: xmin (the primary fit's), all, a value, or N cells ('2cells')")
      ("logbin-max", po::value(&logbin_max)->default_value(logbin_max),
       "upper end of the log-binned slope fit: inf, a value, or N cells ('25cells')")
      ("threads", po::value(&opt.threads)->default_value(0), "threads for the resampling (0: all cores; results do not depend on it)")
      ("histogram-csv", po::value(&histogram_csv),
       "also write the log-binned density histogram as CSV (center,density,count,lower,upper) to this file");
  cli::add_common(desc, common, cli::kOutput | cli::kSeed | cli::kQuiet | cli::kConfig, cli::kOutputHdf5OrText);
  po::positional_options_description positional;
  positional.add("input", -1);
  const auto vm = cli::parse(argc, argv, spec, desc, positional);

  if (input_format != "auto" && input_format != "hdf5" && input_format != "text")
    throw UsageError("--input-format: expected auto, hdf5 or text, got '" + input_format + "'");
  check_one_of(format, {"hdf5", "text"}, "--format");
  analysis::check_fit_options(opt);  // before any input is read
  std::vector<FileRole> input_roles{{"--config", common.config}};
  for (const std::string& input : inputs) input_roles.push_back({"FILE", input});
  check_file_roles(input_roles, {{"-o", common.output}, {"--histogram-csv", histogram_csv}});
  if (ks == "two-sided") opt.scan.ks = analysis::KsConvention::two_sided;
  else if (ks == "powerlaw-r") opt.scan.ks = analysis::KsConvention::powerlaw_r;
  else throw UsageError("--ks: expected two-sided or powerlaw-r, got '" + ks + "'");
  if (vm.count("xmin")) {
    opt.scan.xmin = parse_bound(xmin_text, "--xmin");
    if (!(opt.scan.xmin > 0) || !std::isfinite(opt.scan.xmin)) throw UsageError("--xmin: must be a positive number");
  }
  if (vm.count("xmax")) {
    opt.scan.xmax = parse_bound(xmax_text, "--xmax");
    if (!(opt.scan.xmax > 0)) throw UsageError("--xmax: must be a positive number");
  }
  const auto nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Bound lower = logbin_min == "xmin" ? Bound{nan} : logbin_min == "all" ? Bound{0} : parse_bound_or_cells(logbin_min, "--logbin-min");
  const Bound upper = logbin_max == "inf" ? Bound{inf} : parse_bound_or_cells(logbin_max, "--logbin-max");
  const bool cell_mass_auto = cell_mass_text == "auto";
  if (!cell_mass_auto) opt.cell_mass = parse_bound(cell_mass_text, "--cell-mass");
  opt.compare = !no_compare;
  opt.seed = common.seed;

  ToolRun run = start_run("powerlaw-fit", cli::command_line(argc, argv));
  run.parameters = cli::resolved_options(vm);
  run.seed = std::to_string(common.seed);

  // Input: fragments files, or columns of numbers; several are pooled.
  analysis::FitInput values;
  analysis::DistinctInputs distinct(inputs);
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const std::string& input = inputs[k];
    const bool hdf5 = input_format == "hdf5" || (input_format == "auto" && analysis::input_is_hdf5(input));
    analysis::FitInput one;
    if (hdf5) {
      const io::Group root = io::open_input(input);
      std::int64_t min_cells = 0;
      if (min_cells_text == "file") {
        min_cells = analysis::fragments_min_cells(root);
      } else {
        const double v = parse_bound(min_cells_text, "--min-cells");
        if (!(v >= 0) || v != std::floor(v)) throw UsageError("--min-cells: expected 'file' or a whole number >= 0");
        min_cells = static_cast<std::int64_t>(v);
      }
      distinct.add(k, root);
      one = analysis::read_fragment_values(root, column, min_cells);
      io::add_input(run, root);
    } else {
      if (!vm["column"].defaulted() || !vm["min-cells"].defaulted())
        throw UsageError("--column and --min-cells apply to a fragments file, not to text input");
      one = analysis::read_text_values(input);
    }
    analysis::pool_into(values, one);
  }

  if (cell_mass_auto) opt.cell_mass = values.column == "mass" ? values.mean_cell_mass() : 0.0;
  const double cells_unit = values.column == "cell_count" ? 1.0 : opt.cell_mass;
  opt.logbin_min = lower.resolve(cells_unit, "--logbin-min");
  opt.logbin_max = upper.resolve(cells_unit, "--logbin-max");
  auto report = analysis::fit_powerlaw(values.values, opt, values.source);
  report.spread = analysis::input_spread(values.values, values.input_sizes, report);

  if (!histogram_csv.empty()) {
    std::ostringstream csv;
    analysis::write_histogram_csv(csv, report, provenance_line(run));
    io::write_file_atomically(histogram_csv, csv.str());
  }
  if (format == "text") {
    std::ostringstream text;
    analysis::write_fit_text(text, report, values, provenance_line(run));
    io::write_file_atomically(common.output, text.str());
  } else {
    io::OutputFile out(common.output);
    io::write_header(out.root(), "fit", run, out.uuid());
    analysis::write_fit(out.root(), report, values);
    out.commit();
  }
  if (!common.quiet) {
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
