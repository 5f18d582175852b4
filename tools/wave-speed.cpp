// wave-speed: measured wave speeds of a run (front arrival against distance, fitted by a straight line),
// and the continuum prediction for the same material and stretch: the Mooney-Rivlin sheet for the rubber
// lattice, plane stress with measured elastic constants for the polygon DEM. docs/wave-speed.md.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "analysis/wave_speed.hpp"
#include "analysis/wave_speed_report.hpp"
#include "analysis/wave_speed_theory.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/option_check.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/speeds_io.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

// "A:B", either side may be empty (NaN); for --range and --time.
std::array<double, 2> parse_interval(const std::string& text, const std::string& option) {
  const auto colon = text.find(':');
  std::array<double, 2> out{analysis::kNaN, analysis::kNaN};
  bool ok = colon != std::string::npos;
  for (int k = 0; ok && k < 2; ++k) {
    const std::string part = k == 0 ? text.substr(0, colon) : text.substr(colon + 1);
    if (part.empty()) continue;
    std::istringstream in(part);
    in >> out[k];
    ok = static_cast<bool>(in) && in.peek() == std::char_traits<char>::eof() && std::isfinite(out[k]);
  }
  if (!ok) throw UsageError(option + ": expected MIN:MAX (either may be left out), got '" + text + "'");
  return out;
}
// Every option's value, as parsed.
struct Options {
  cli::CommonOptions common;
  std::string input, format = "hdf5", signal = "displacement", arrival = "threshold", amplitude = "local",
                     side = "both", source, range, time, stretch, rows_along, theory;
  std::vector<std::string> directions, modes;
  analysis::FrontOptions front;
  bool no_interpolate = false;
  double a = 0, b = 0, density = 0, young = 0, poisson = 0, spacing = 0, short_width = 0, cutoff = 0, cutoff_width = 0;
  po::variables_map vm;
};

cli::ToolSpec tool_spec() {
  return {"wave-speed", "[options] RUN|-   or   wave-speed --theory [mooney-rivlin|dem] [options]",
          "Measures the longitudinal and shear wave speeds of a run (rubber-run or dem-run): the arrival time of "
          "the front (first time the displacement, velocity or strain at a distance reaches a fraction of the pulse "
          "amplitude) at many distances from the source along the chosen directions, fitted by a straight line, "
          "gives the lab speed with its standard error. Unset options are taken from the run's /parameters, mesh and "
          "first frame. The measurement is compared with the long-wavelength speeds of the Mooney-Rivlin sheet at "
          "the same stretch (rubber; only when every bond of the lattice is in its Mooney-Rivlin range, else it says "
          "why not) or with the plane-stress speeds of measured elastic constants (DEM: c_L = sqrt(K/(rho(1-nu^2))), "
          "c_S = sqrt(K/(2 rho(1+nu)))). With --theory and no run, prints the prediction alone. Writes an HDF5 file "
          "of kind speeds, or key value lines with --format text.",
          "  wave-speed wave.h5 --direction x --mode shear --format text\n"
          "  mesh-gen triangular --nodes 400x40 --spacing 1 | rubber-run --scene data/scenes/wave.ini - -o wave.h5 && "
          "wave-speed wave.h5 -o speeds.h5\n"
          "  wave-speed pulse.h5 --direction radial --theory dem --young 4.1e8 --poisson 0.2 --format text\n"
          "  wave-speed --theory --a 1 --b 1.5 --density 1 --stretch 1.5x3 --format text\n"
          "  wave-speed --theory dem --young 4.1e8 --poisson 0.2 --density 5000 --format text"};
}

void add_measure_options(po::options_description& desc, Options& o) {
  po::options_description measure("Measurement (a run)");
  measure.add_options()("input", po::value(&o.input), "run file (rubber-run or dem-run), or - for standard input")(
      "direction", po::value(&o.directions)->composing(),
      "propagation direction: x, y, -x, -y, an angle in degrees, or radial (from a point source); repeatable "
      "(default: the run's loading.pulse_direction, radial for the DEM pulse and explosion scenes, else x)")(
      "mode", po::value(&o.modes)->composing(),
      "longitudinal, shear or auto (each mode present in the signal); repeatable (default: the run's "
      "loading.pulse, else auto)")(
      "signal", po::value(&o.signal)->default_value(o.signal),
      "displacement (from the first frame), velocity, or strain (link strain change; needs --mode)")(
      "source", po::value(&o.source),
      "source position XxY in m, lab frame (default: velocity-weighted centroid of the "
      "first frame in which something moves); write --source=-1x2 for negative values")(
      "threshold", po::value(&o.front.threshold)->default_value(0.5), "arrival level, fraction of the amplitude")(
      "arrival", po::value(&o.arrival)->default_value(o.arrival),
      "threshold (the front: first time the level is reached) or peak (the first maximum after that)")(
      "amplitude", po::value(&o.amplitude)->default_value(o.amplitude),
      "what the threshold is a fraction of: local (each distance's own peak), global (the strongest peak), or "
      "a number (m, m/s or 1, by signal)")(
      "floor", po::value(&o.front.floor)->default_value(1e-3),
      "distances whose peak is below this fraction of the strongest have no arrival")(
      "bin", po::value(&o.front.bin)->default_value(0.0), "bin width in m along the direction (0: median link length)")(
      "lateral", po::value(&o.front.lateral)->default_value(0.0),
      "half-width in m of the band around the ray through the source (0: no limit)")(
      "range", po::value(&o.range),
      "distances from the source fitted, MIN:MAX in m (default 0.25 to 0.95 of the "
      "farthest receiver)")("time", po::value(&o.time), "frames used, TMIN:TMAX in s (default: all)")(
      "side", po::value(&o.side)->default_value(o.side), "both (distances folded), forward or backward of the source")(
      "reject", po::value(&o.front.reject)->default_value(4.0),
      "drop arrivals further than this many robust standard deviations from the line (0: keep all)")(
      "no-interpolate", po::bool_switch(&o.no_interpolate), "arrival = first frame at or above the level");
  desc.add(measure);
}

void add_theory_options(po::options_description& desc, Options& o) {
  po::options_description theory_opts("Prediction");
  theory_opts.add_options()(
      "theory", po::value(&o.theory)->implicit_value("mooney-rivlin"),
      "mooney-rivlin (default when given alone) or dem; without a run, print the prediction alone")(
      "a", po::value(&o.a), "Mooney-Rivlin a in m^2/s^2 (default: the run's material.a)")(
      "b", po::value(&o.b), "Mooney-Rivlin b (default: the run's material.b)")(
      "density", po::value(&o.density),
      "Mooney-Rivlin: areal density in kg/m^2 (enters the stresses only); dem: density in kg/m^3")(
      "stretch", po::value(&o.stretch),
      "extension ratios LXxLY (default: the run's scene, else its first frame; "
      "theory alone: 1x1)")("young", po::value(&o.young),
                            "dem: Young modulus K in Pa measured on the DEM (elastic-moduli scene)")(
      "poisson", po::value(&o.poisson), "dem: Poisson ratio measured on the DEM")(
      "spacing", po::value(&o.spacing), "lattice spacing Delta in m, for the lattice check (default: the run's mesh)")(
      "rows-along", po::value(&o.rows_along), "close-packed rows along x or y (default: the run's mesh, else x)")(
      "short-width", po::value(&o.short_width),
      "short-bond width u_s in m: bonds shorter than Delta + u_s are not "
      "Mooney-Rivlin (default: the run's scene)")("cutoff", po::value(&o.cutoff),
                                                  "bond cut-off u_c in m (default: the run's scene)")(
      "cutoff-width", po::value(&o.cutoff_width), "width of the cut-off in m (default: the run's scene)");
  desc.add(theory_opts);
}

void parse_options(int argc, char** argv, Options& o) {
  po::options_description desc;
  add_measure_options(desc, o);
  add_theory_options(desc, o);
  po::options_description out_opts("Output");
  out_opts.add_options()("format", po::value(&o.format)->default_value(o.format), "hdf5 or text (key value lines)");
  cli::add_common(out_opts, o.common, cli::kOutput | cli::kQuiet | cli::kConfig, cli::kOutputHdf5OrText);
  desc.add(out_opts);
  po::positional_options_description positional;
  positional.add("input", 1);
  o.vm = cli::parse(argc, argv, tool_spec(), desc, positional);
}

// The prediction's inputs given on the command line (the rest come from the run, or are missing).
analysis::TheoryInputs theory_inputs(const Options& o) {
  const po::variables_map& vm = o.vm;
  analysis::TheoryInputs th;
  if (vm.count("theory")) th.theory = analysis::parse_theory(o.theory, "--theory");
  const auto opt = [&](const char* key, double v, std::optional<double>& into) {
    if (vm.count(key)) into = v;
  };
  opt("a", o.a, th.a);
  opt("b", o.b, th.b);
  opt("density", o.density, th.density);
  opt("young", o.young, th.young);
  opt("poisson", o.poisson, th.poisson);
  opt("spacing", o.spacing, th.spacing);
  opt("short-width", o.short_width, th.short_width);
  opt("cutoff", o.cutoff, th.cutoff);
  opt("cutoff-width", o.cutoff_width, th.cutoff_width);
  if (vm.count("rows-along")) th.rows_along = o.rows_along;
  if (vm.count("stretch")) {
    const auto s = cli::parse_pair_double(o.stretch, "--stretch");
    th.stretch = analysis::Stretch{s[0], s[1]};
  }
  return th;
}

// The measurement asked for: the front options, the directions and modes given, the prediction's inputs.
analysis::RunRequest run_request(const Options& o, const analysis::TheoryInputs& th, const std::vector<double>& dirs) {
  const po::variables_map& vm = o.vm;
  analysis::RunRequest req;
  req.theory = th;
  req.front.signal = analysis::parse_signal(o.signal, "--signal");
  req.front.side = analysis::parse_side(o.side, "--side");
  req.front.arrival = analysis::parse_arrival(o.arrival, "--arrival");
  req.front.threshold = o.front.threshold;
  req.front.floor = o.front.floor;
  req.front.bin = o.front.bin;
  req.front.lateral = o.front.lateral;
  req.front.reject = o.front.reject;
  req.front.interpolate = !o.no_interpolate;
  analysis::parse_amplitude(o.amplitude, "--amplitude", req.front);
  if (!dirs.empty()) {
    req.front.directions = dirs;
    req.directions_given = true;
  }
  for (const auto& m : o.modes) {
    if (m == "auto") continue;  // with no other mode: automatic, whatever the run's scene says
    req.front.modes.push_back(analysis::parse_wave_mode(m, "--mode"));
  }
  req.modes_given = !o.modes.empty();
  if (vm.count("source")) {
    const auto s = cli::parse_pair_double(o.source, "--source");
    req.front.source = Eigen::Vector2d(s[0], s[1]);
  }
  if (vm.count("range")) {
    const auto r = parse_interval(o.range, "--range");
    req.front.s_min = r[0];
    req.front.s_max = r[1];
  }
  if (vm.count("time")) {
    const auto t = parse_interval(o.time, "--time");
    if (std::isfinite(t[0])) req.front.t_min = t[0];
    if (std::isfinite(t[1])) req.front.t_max = t[1];
  }
  return req;
}

int body(int argc, char** argv) {
  Options o;
  parse_options(argc, argv, o);
  check_one_of(o.format, {"hdf5", "text"}, "--format");
  check_file_roles({{"RUN", o.input}, {"--config", o.common.config}}, {{"-o", o.common.output}});
  const bool have_run = o.vm.count("input") > 0;
  if (!have_run && !o.vm.count("theory"))
    throw UsageError("give a run file (or - for standard input), or --theory for the prediction alone");
  analysis::TheoryInputs th = theory_inputs(o);
  std::vector<double> dirs;
  for (const auto& d : o.directions) dirs.push_back(analysis::parse_direction(d, "--direction"));

  ToolRun run = start_run("wave-speed", cli::command_line(argc, argv));
  run.parameters = cli::resolved_options(o.vm);
  io::SpeedsRecord record;
  std::vector<std::string> notes;
  std::optional<io::Group> input_root;
  if (!have_run) {
    th.directions = dirs;
    record = analysis::predict_speeds(th);
  } else {
    const analysis::RunRequest req = run_request(o, th, dirs);
    input_root.emplace(io::open_input(o.input));
    io::check_header(*input_root, {"run"});
    io::add_input(run, *input_root);
    record = analysis::measure_and_compare(*input_root, req, notes);
  }

  if (!o.common.quiet) {
    for (const auto& n : notes) std::cerr << "wave-speed: " << n << "\n";
    if (!record.lattice_regime.empty() && record.lattice_regime != "mooney-rivlin")
      std::cerr << "wave-speed: warning: " << record.lattice_message << "\n";
  }
  io::write_speeds_file(o.common.output, record, run, o.format == "text");
  if (o.format != "text" && !o.common.quiet)
    std::cerr << "wave-speed: wrote " << (o.common.output == "-" ? "standard output" : o.common.output) << "\n";
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("wave-speed", [&] { return body(argc, argv); });
}
