// fragment-count: the fragments of a polygon-DEM run (clusters of cells joined by intact beams) with
// their masses, sizes, centres of mass, velocities and kinetic energies, the log-binned histogram of
// their masses and, on request, the number of fragments over the run. Layout: docs/fragments.md.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "analysis/fragments.hpp"
#include "analysis/fragments_io.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

struct Options {
  std::string input;
  long long frame = -1;
  double time = 0.0;
  bool by_time = false, by_frame = false;
  long long min_cells = 1;
  double bins_per_decade = 5;
  bool time_series = false;
  cli::CommonOptions common;
};

// The frame index the options pick (0 <= k < frames).
std::int64_t pick_frame(const Options& o, const io::RunInfo& info, const std::string& file) {
  const auto frames = static_cast<long long>(info.step.size());
  if (o.by_time) return frame_at_time(info, o.time);
  const long long k = o.frame < 0 ? frames + o.frame : o.frame;
  if (k < 0 || k >= frames)
    throw UsageError("--frame " + std::to_string(o.frame) + ": out of range, " + file + " holds " +
                     std::to_string(frames) + " frames (0.." + std::to_string(frames - 1) + ", or -" +
                     std::to_string(frames) + "..-1 from the end)");
  return k;
}

std::string summary(const analysis::FragmentRecord& r) {
  const auto& f = r.fragments;
  std::ostringstream s;
  s << "frame " << r.frame << " (step " << r.step << ", t = " << r.time << " s): " << f.fragments() << " fragments";
  if (r.min_cells > 1) s << " (" << f.count_at_least(r.min_cells) << " of >= " << r.min_cells << " cells)";
  const double largest = f.fragments() && f.total_mass > 0 ? f.mass[0] / f.total_mass : 0.0;
  s << ", largest " << std::setprecision(4) << 100.0 * largest << "% of the mass, " << f.singles() << " single cells";
  return s.str();
}

int run(int argc, const char* const* argv) {
  ToolRun run = start_run("fragment-count", cli::command_line(argc, argv));
  const cli::ToolSpec spec{
      "fragment-count", "[options] RUN|-",
      "Finds the fragments of a polygon-DEM run: the clusters of cells joined by intact beams (contacts do "
      "not bind), in the final state or in the frame chosen by --frame or --time. Writes a fragments file "
      "(docs/fragments.md): the fragment of each cell; per fragment its mass, cell count, centre of mass, "
      "centre-of-mass velocity, translational kinetic energy and rotational kinetic energy (the kinetic "
      "energy in the fragment's centre-of-mass frame: spin of the cells plus their motion about the centre "
      "of mass); fragments sorted by mass, largest first. Every fragment is listed; --min-cells selects "
      "those the mass histogram, the time series and a power-law fit count.",
      "  fragment-count explosion.h5 -o fragments.h5\n"
      "  fragment-count explosion.h5 --time 2e-3 --min-cells 2 --time-series -o fragments.h5\n"
      "  dem-run --scene explosion.ini disc.h5 | fragment-count - | powerlaw-fit - --format text"};
  Options o;
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&o.input)->required(), "run file, or - for standard input")(
      "frame", po::value(&o.frame), "frame index; negative counts from the end (-1: the final state, the default)")(
      "time", po::value(&o.time), "use the frame whose time is closest to T (s)")(
      "min-cells", po::value(&o.min_cells)->default_value(1),
      "smallest fragment (in cells) counted in the histogram, the time series and the fit selection; "
      "2 leaves single cells out")("bins-per-decade", po::value(&o.bins_per_decade)->default_value(5),
                                   "bins per decade of the mass histogram")(
      "time-series", po::bool_switch(&o.time_series),
      "also count the fragments and the largest fragment's mass in every frame of the run");
  cli::add_common(desc, o.common, cli::kOutput | cli::kQuiet | cli::kConfig);
  po::positional_options_description positional;
  positional.add("input", 1);
  const auto vm = cli::parse(argc, argv, spec, desc, positional);
  o.by_frame = vm.count("frame") > 0;
  o.by_time = vm.count("time") > 0;
  if (o.by_frame && o.by_time) throw UsageError("--frame and --time: give one or the other");
  if (o.by_time && !std::isfinite(o.time)) throw UsageError("--time: must be a finite number of seconds");
  if (o.min_cells < 1) throw UsageError("--min-cells: must be at least 1, got " + std::to_string(o.min_cells));
  if (!(o.bins_per_decade > 0 && o.bins_per_decade <= 1000))
    throw UsageError("--bins-per-decade: must be in (0, 1000], got " +
                     (std::ostringstream() << o.bins_per_decade).str());
  check_file_roles({{"RUN", o.input}, {"--config", o.common.config}}, {{"-o", o.common.output}});

  const io::Group root = io::open_input(o.input);
  io::check_header(root, {"run"});
  const io::RunInfo info = analysis::read_dem_run_info(root);
  const auto frame = pick_frame(o, info, root.file());
  const analysis::FragmentInput in = analysis::read_fragment_input(root, info, frame);

  analysis::FragmentRecord rec;
  rec.frame = in.frame;
  rec.step = in.step;
  rec.time = in.time;
  rec.min_cells = o.min_cells;
  rec.fragments = analysis::find_fragments(in.state());
  rec.histogram = analysis::mass_histogram(rec.fragments, o.min_cells, o.bins_per_decade);

  if (o.time_series) rec.time_series = analysis::fragment_time_series(root, info, in.beam, o.min_cells);

  run.parameters = cli::resolved_options(vm);
  io::add_input(run, root);
  io::OutputFile out(o.common.output);
  io::write_header(out.root(), "fragments", run, out.uuid());
  analysis::write_fragments(out.root(), rec);
  out.commit();
  if (!o.common.quiet) std::cerr << "fragment-count: " << summary(rec) << "\n";
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("fragment-count", [&] { return run(argc, argv); });
}
