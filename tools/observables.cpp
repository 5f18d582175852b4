// observables: a run's observables as a table, and straight-line fits between them (elastic moduli).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "analysis/crack_report.hpp"
#include "analysis/observable_table.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/provenance_text.hpp"

using namespace frac;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  return cli::run_tool("observables", [&] {
    const cli::ToolSpec spec{
        "observables", "RUN.h5 [--columns a,b,...] [--fit Y:X [--where X>0] [--after T]]",
        "Prints the observables of a run (dem-run, rubber-run) as CSV on standard output: a '#' line with the "
        "provenance, the header, then time and the named columns (default: all scalar observables). With --fit "
        "Y:X, fits Y = intercept + slope·X by least squares over the samples selected by --where and --after and "
        "prints `key value` lines: slope, slope_stderr, intercept, points (the elastic moduli: --fit "
        "stress:axial_strain gives K; --fit lateral_strain:axial_strain gives −ν). With --crack-shape (a rubber-run "
        "crack run), measures the crack in one frame and prints `key value` lines: the tip, the angle of the front "
        "behind which the sheet unloads (the wedge), how far it trails the tip, broken bonds, the grips. The `key "
        "value` "
        "outputs start with the same '#' provenance line.",
        "  observables run.h5 --columns stress,axial_strain > curve.csv\n"
        "  observables run.h5 --fit stress:axial_strain --where 'axial_strain>0' --after 2e-3\n"
        "  observables crack.h5 --crack-shape --time 1.5e-3"};
    cli::CommonOptions common;
    std::string input, columns, fit, where, parameter, compare;
    double after = -std::numeric_limits<double>::infinity();
    double time = std::numeric_limits<double>::quiet_NaN();
    bool crack_shape = false;
    po::options_description desc("Options");
    desc.add_options()("input", po::value(&input)->required(), "run file, or - for standard input")(
        "columns", po::value(&columns), "comma-separated observable names (default: every scalar one)")(
        "fit", po::value(&fit), "Y:X, fit Y against X")(
        "where", po::value(&where), "select samples: NAME>VALUE or NAME<VALUE")("after", po::value(&after),
                                                                                "select samples at time > T (s)")(
        "parameter", po::value(&parameter), "print the value of a resolved parameter of the run (e.g. derived.dt)")(
        "compare", po::value(&compare),
        "REFERENCE.h5: print the rms and largest distance between the final positions of the two runs (same mesh)")(
        "crack-shape", po::bool_switch(&crack_shape),
        "measure the crack of a rubber-run crack run in one frame (docs/rubber-run.md, \"Crack experiment\")")(
        "time", po::value(&time), "with --crack-shape: the frame nearest this time, in s (default: the final state)");
    cli::add_common(desc, common, cli::kQuiet | cli::kConfig);
    po::positional_options_description positional;
    positional.add("input", 1);
    cli::parse(argc, argv, spec, desc, positional);

    const io::Group root = io::open_input(input);
    io::check_header(root, {"run"});
    ToolRun run = start_run("observables", cli::command_line(argc, argv));
    io::add_input(run, root);
    // The "key value" outputs start with the provenance as a '#' line, like the CSV (awk '$1 == "key"' skips it).
    const auto provenance = [&run] { return io::csv_comment(provenance_line(run)); };
    if (!compare.empty()) {
      const io::Group reference = io::open_input(compare);
      io::check_header(reference, {"run"});
      io::add_input(run, reference);
      const analysis::PositionDifference d = analysis::compare_final_positions(root, reference, input, compare);
      std::cout << provenance() << std::setprecision(10) << "rms_position_difference " << d.rms
                << "\nmax_position_difference " << d.max << "\ntime " << d.time << "\nreference_time "
                << d.reference_time << "\n";
      return kExitOk;
    }
    if (crack_shape) {
      const analysis::CrackReport report = analysis::crack_report(root, time);
      std::cout << provenance();
      analysis::write_key_values(report, std::cout);
      return kExitOk;
    }
    if (!parameter.empty()) {
      std::cout << analysis::run_parameter(root, parameter) << "\n";
      return kExitOk;
    }
    const analysis::ObservableTable table = analysis::read_observables(root, analysis::split_names(columns));
    if (fit.empty()) {
      analysis::write_csv(table, std::cout, provenance_line(run));
      return kExitOk;
    }
    const auto colon = fit.find(':');
    if (colon == std::string::npos) throw UsageError("--fit: expected Y:X, got '" + fit + "'");
    const auto selection = analysis::select_rows(table, where, after, input);
    const analysis::LineFit f =
        analysis::fit_columns(table, fit.substr(0, colon), fit.substr(colon + 1), selection, input);
    std::cout << provenance() << std::setprecision(10) << "slope " << f.slope << "\nslope_stderr " << f.slope_stderr
              << "\nintercept " << f.intercept << "\npoints " << f.points << "\n";
    return kExitOk;
  });
}
