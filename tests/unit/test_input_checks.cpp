// Validation of what a user gives the tools: options (Boost's gaps: negative unsigned values, NaN and
// infinities, missing values and inputs), scene values against their ranges and the physical limits, the
// keys a run needs, kicks too fast for any solid, and runs that run away. Each test names the fault the
// message must name.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "analysis/powerlaw.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/progress.hpp"
#include "core/provenance.hpp"
#include "core/scene.hpp"
#include "dem/scene.hpp"
#include "dem/simulation.hpp"
#include "dynamics/runaway.hpp"
#include "io/checkpoint.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"
#include "mesh/random_lattice.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/setup.hpp"
#include "run/driver.hpp"

namespace {

using namespace frac;
namespace fs = std::filesystem;
namespace po = boost::program_options;

// The message of the UsageError (or InputError, RuntimeError) `f` throws; "(no error)" if none.
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

// A small tool's command line: --count (unsigned), --level (double), an input.
struct Tool {
  unsigned count = 0;
  double level = 0;
  std::string input, config;
  po::options_description desc{"Options"};
  po::positional_options_description positional;
  Tool() {
    desc.add_options()("count", po::value(&count), "")("level", po::value(&level), "")(
        "input", po::value(&input)->required(), "")("config", po::value(&config), "");
    positional.add("input", 1);
  }
  void parse(std::vector<const char*> args) {
    args.insert(args.begin(), "tool");
    cli::parse(static_cast<int>(args.size()), args.data(), {"tool", "IN [options]", "", ""}, desc, positional);
  }
};

// The scene keys a command line (and its --config file) give, as dem-run collects them: the file's first.
std::vector<std::pair<std::string, std::string>> scene_keys(std::vector<const char*> args) {
  args.insert(args.begin(), "tool");
  std::vector<std::pair<std::string, std::string>> keys;
  const auto rest = cli::split_overrides(static_cast<int>(args.size()), args.data(), keys);
  Tool t;
  cli::parse(static_cast<int>(rest.size()), rest.data(), {"tool", "IN [options]", "", ""}, t.desc, t.positional, &keys);
  return keys;
}

// A file of `text` in a fresh temporary folder.
fs::path temp_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("fracture-test-config-" + make_uuid().substr(0, 8));
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

std::string data_scene(const std::string& name) {
  return (fs::path(__FILE__).parent_path().parent_path().parent_path() / "data" / "scenes" / (name + ".ini")).string();
}

dem::DemScene dem_scene(const std::string& name, const std::vector<std::pair<std::string, std::string>>& set) {
  Scene s = Scene::load(data_scene(name), set);
  return dem::read_dem_scene(s);
}

mesh::CellMesh block() {
  mesh::RandomLatticeOptions o;
  o.width = 0.1, o.height = 0.1, o.nx = 10, o.ny = 10, o.seed = 3;
  return mesh::make_random_lattice(o);
}

}  // namespace

TEST(OptionParsing, RefusesWhatBoostLetsThrough) {
  Tool t;
  EXPECT_EQ(error_of([&] { t.parse({"in.h5", "--count", "-1"}); }), "--count: must not be negative, got '-1'");
  Tool u;
  EXPECT_EQ(error_of([&] { u.parse({"in.h5", "--level", "nan"}); }), "--level: must be a finite number, got 'nan'");
  Tool v;
  EXPECT_EQ(error_of([&] { v.parse({"in.h5", "--level", "-inf"}); }), "--level: must be a finite number, got '-inf'");
  Tool w;
  EXPECT_EQ(error_of([&] { w.parse({"in.h5", "--level", "2.5", "--count", "3"}); }), "(no error)");
  EXPECT_EQ(w.count, 3u);
  EXPECT_EQ(w.level, 2.5);
}

TEST(OptionParsing, NamesTheMissingValueOrInput) {
  Tool t;
  EXPECT_EQ(error_of([&] { t.parse({"in.h5", "--level"}); }), "--level: missing value");
  Tool u;
  EXPECT_EQ(error_of([&] { u.parse({"--level", "1"}); }), "no input given (usage: tool IN [options])");
  Tool v;
  EXPECT_EQ(error_of([&] { v.parse({"a.h5", "b.h5"}); }).rfind("more arguments than inputs: 'a.h5', 'b.h5'", 0), 0u);
}

TEST(OptionParsing, ConfigFileValuesAreCheckedToo) {
  const fs::path path = fs::temp_directory_path() / ("fracture-test-config-" + make_uuid().substr(0, 8) + ".cfg");
  std::ofstream(path) << "level = inf\n";
  Tool t;
  EXPECT_EQ(error_of([&] {
              t.parse({"in.h5", "--config", path.c_str()});
            }),
            "--config " + path.string() + ": --level: must be a finite number, got 'inf'");
  fs::remove(path);
}

TEST(OptionParsing, EachSceneKeyOnceOnTheCommandLineAndOnceInTheConfigFile) {
  EXPECT_EQ(error_of([] {
              scene_keys({"in.h5", "--material.t_eps", "0.02", "--material.t_eps=0.03"});
            }),
            "--material.t_eps: given twice on the command line ('0.02', then '0.03')");
  const fs::path twice = temp_file("twice.cfg", "material.t_eps = 0.02\n[material]\nt_eps = 0.03\n");
  EXPECT_EQ(error_of([&] {
              scene_keys({"in.h5", "--config", twice.c_str()});
            }),
            "--config " + twice.string() + ": key 'material.t_eps' is given twice");
  // In the file and on the command line: the command line's comes last, and wins.
  const fs::path once = temp_file("once.cfg", "[material]\nt_eps = 0.02\n");
  const auto keys = scene_keys({"in.h5", "--config", once.c_str(), "--material.t_eps", "0.03"});
  ASSERT_EQ(keys.size(), 2u);
  Scene s = Scene::parse("[material]\nt_eps = 0.01\n", "s.ini");
  for (const auto& [key, value] : keys) s.set(key, value);
  EXPECT_EQ(s.number("material.t_eps"), 0.03);
  fs::remove_all(twice.parent_path());
  fs::remove_all(once.parent_path());
}

TEST(OptionParsing, TheConfigFileIsOneRegularTextFile) {
  const fs::path nested = temp_file("nested.cfg", "config = other.cfg\n");
  Tool t;
  EXPECT_EQ(error_of([&] {
              t.parse({"in.h5", "--config", nested.c_str()});
            }),
            "--config " + nested.string() + ": 'config' cannot be set inside a config file (give one --config)");
  const std::string dir = nested.parent_path().string();
  Tool u;
  EXPECT_EQ(error_of([&] {
              u.parse({"in.h5", "--config", dir.c_str()});
            }),
            "--config " + dir + ": is a directory, not a file of 'key = value' lines");
  Tool v;
  EXPECT_EQ(error_of([&] {
              v.parse({"in.h5", "--config", "/dev/null"});
            }),
            "--config /dev/null: not a regular file of 'key = value' lines");
  const fs::path binary = temp_file("binary.cfg", std::string("level = 1\n\0\x01", 12));
  Tool w;
  EXPECT_NE(error_of([&] {
              w.parse({"in.h5", "--config", binary.c_str()});
            }).find("holds a NUL byte"),
            std::string::npos);
  fs::remove_all(nested.parent_path());
  fs::remove_all(binary.parent_path());
}

TEST(OptionCheck, IntervalsSayTheirEnds) {
  EXPECT_EQ(error_of([] { check_in(2, "--significance", Interval::open(0, 1)); }),
            "--significance: must lie in (0, 1), got 2");
  EXPECT_EQ(error_of([] { check_in(0, "--x", Interval::open_closed(0, 5)); }), "--x: must lie in (0, 5], got 0");
  EXPECT_EQ(error_of([] { check_in(std::nan(""), "--x", Interval::closed(0, 5)); }),
            "--x: must lie in [0, 5], got nan");
  EXPECT_EQ(error_of([] { check_in(5, "--x", Interval::closed(0, 5)); }), "(no error)");
  EXPECT_FALSE(Interval::closed(0, 1).contains(std::numeric_limits<double>::infinity()));
}

TEST(SceneChecks, RangesNameTheKeyAndItsOrigin) {
  Scene s = Scene::parse("[material]\ndensity = 1e9\n", "s.ini");
  EXPECT_EQ(error_of([&] { s.in("material.density", 1, Interval::open_closed(0, 1e5)); }),
            "s.ini: material.density = '1e9': must lie in (0, 100000]");
  s.set("material.density", "-2");
  EXPECT_EQ(error_of([&] { s.in("material.density", 1, Interval::open_closed(0, 1e5)); }),
            "--material.density = '-2': must be positive");
  EXPECT_EQ(error_of([&] { s.require("loading.kind", "what the run does"); }),
            "s.ini: loading.kind is required (what the run does)");
}

TEST(SceneChecks, EmptySceneFileAndMissingKindAreRefused) {
  const fs::path dir = fs::temp_directory_path() / ("fracture-test-scene-" + make_uuid().substr(0, 8));
  fs::create_directories(dir);
  std::ofstream(dir / "empty.ini") << "# nothing\n\n";
  EXPECT_NE(error_of([&] { Scene::load((dir / "empty.ini").string()); }).find("empty.ini: the scene file sets no keys"),
            std::string::npos);
  std::ofstream(dir / "kindless.ini") << "[material]\ndensity = 5000\n";
  const Scene kindless = Scene::load((dir / "kindless.ini").string());
  EXPECT_NE(error_of([&] { dem::require_run_keys(kindless); }).find("kindless.ini: loading.kind is required"),
            std::string::npos);
  EXPECT_NE(error_of([&] { rubber::require_run_keys(kindless); }).find("kindless.ini: loading.kind is required"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(SceneChecks, DemValuesBeyondThePhysicalLimits) {
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"material.density", "1e9"}});
            }),
            "--material.density = '1e9': must lie in (0, 100000]");
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"material.beam_modulus", "1e20"}});
            }),
            "--material.beam_modulus = '1e20': must lie in (0, 1e+13]");
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"material.gamma_n", "1e12"}});
            }),
            "--material.gamma_n = '1e12': must lie in [0, 1e+09]");
  EXPECT_EQ(error_of([] {
              dem_scene("impact", {{"loading.impact_speed", "1e6"}});
            }),
            "--loading.impact_speed = '1e6': must lie in (0, 100000]");
  EXPECT_NE(error_of([] {
              dem_scene("explosion", {{"stop.steps_without_breaking", "-1"}});
            }).find("stop.steps_without_breaking must not be negative"),
            std::string::npos);
  // Out-of-reach thresholds are a way to switch breaking off, not an error.
  EXPECT_EQ(error_of([] { dem_scene("explosion", {{"material.t_eps", "1e300"}}); }), "(no error)");
}

TEST(SceneChecks, ModuliOfZeroAndStepsThatNeverReachTheEnd) {
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"material.beam_modulus", "0"}});
            }),
            "--material.beam_modulus = '0': must be positive");
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"material.grain_modulus", "0"}});
            }),
            "--material.grain_modulus = '0': must be positive");
  EXPECT_EQ(error_of([] {
              dem_scene("explosion", {{"integrator.dt", "1e-300"}});
            }),
            "--integrator.dt = '1e-300': 5e+297 steps to reach stop.t_max = 0.005 s, more than 1e+12");
  EXPECT_EQ(error_of([] { dem_scene("explosion", {{"integrator.dt", "1e-14"}}); }), "(no error)");  // 5e11 steps
  const mesh::NodeMesh m = mesh::make_triangular_lattice({20, 10, 1e-3, "x", 0.0});
  Scene s = Scene::parse("[integrator]\ndt = 1e-300\n[stop]\nt_max = 1e-3\n", "r.ini");
  EXPECT_EQ(error_of([&] { rubber::read_rubber_scene(s, m); }),
            "r.ini: integrator.dt = '1e-300': 1e+297 steps to reach stop.t_max = 0.001 s, more than 1e+12");
}

TEST(SceneChecks, KicksFasterThanAnySolidAreRefused) {
  const mesh::CellMesh m = block();
  EXPECT_NE(error_of([&] {
              dem::Simulation(m, dem_scene("explosion", {{"loading.energy", "1e300"}}));
            }).find("loading.energy = 1e+300 J: kicks cell "),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              dem::Simulation(m, dem_scene("impact", {{"loading.impact_energy", "1e12"}}));
            }).find("loading.impact_energy = 1e+12 J: kicks cell "),
            std::string::npos);
  EXPECT_EQ(error_of([&] { dem::Simulation(m, dem_scene("explosion", {{"loading.energy", "500"}})); }), "(no error)");
  EXPECT_EQ(error_of([&] {
              dem::Simulation(m, dem_scene("uniaxial", {{"loading.layer_depth", "0.06"}}));
            }),
            "loading.layer_depth = 0.06 m: the boundary layers would meet (the sample is 0.1 x 0.1 m)");
  EXPECT_EQ(error_of([&] {
              dem::Simulation(m, dem_scene("impact", {{"loading.impact_width", "0.2"}}));
            }),
            "loading.impact_width = 0.2 m: wider than the sample (0.1 m)");
}

TEST(SceneChecks, RubberValuesBeyondTheSheetOrTheLimits) {
  const mesh::NodeMesh m = mesh::make_triangular_lattice({20, 10, 1e-3, "x", 0.0});
  auto read = [&](const std::string& text) {
    Scene s = Scene::parse(text, "r.ini");
    rubber::read_rubber_scene(s, m);
  };
  EXPECT_EQ(error_of([&] { read("[loading]\nstretch_y = 1e6\n"); }),
            "r.ini: loading.stretch_y = '1e6': must lie in (0, 100]");
  EXPECT_EQ(error_of([&] { read("[initial]\nnoise = 1e7\n"); }),
            "r.ini: initial.noise = '1e7': must lie in [0, 100000]");
  EXPECT_EQ(error_of([&] { read("[material]\na = 1e20\n"); }), "r.ini: material.a = '1e20': must lie in (0, 1e+10]");
  // The pulse's amplitude must fit on the 19.5 x 7.8 mm sheet.
  EXPECT_EQ(error_of([&] { read("[pulse]\namplitude = 1\n"); }),
            "r.ini: pulse.amplitude = '1': must lie in [0, 0.0195]");
  EXPECT_EQ(error_of([&] { read("[law]\ncutoff_length = 10\n"); }),
            "r.ini: law.cutoff_length = '10': must lie in (0, 1]");
  EXPECT_EQ(error_of([&] { read("[loading]\nstretch_y = 3\n"); }), "(no error)");
}

TEST(Runaway, NamesTheStepAndTheBody) {
  // Three cells at (0, 0), (1, 0), (0, 1) m (x of each, then y, then angles): a box of 1 m.
  const std::vector<double> q0{0, 1, 0, 0, 0, 1, 0, 0, 0};
  const dynamics::RunawayGuard guard(q0, 3, "cell");
  std::vector<double> q = q0;
  q[1] = 500;  // within 1000 sizes
  EXPECT_EQ(error_of([&] { guard.check(q, 7, 1e-3); }), "(no error)");
  q[2 + 3] = -2e3;  // cell 2, y
  EXPECT_EQ(
      error_of([&] { guard.check(q, 7, 1e-3); }).rfind("runaway at step 7 (t = 0.001 s): cell 2 is at (0, -2000) m", 0),
      0u);
  q[2 + 3] = 1;
  q[0] = std::nan("");
  EXPECT_EQ(
      error_of([&] { guard.check(q, 8, 2e-3); }).rfind("runaway at step 8 (t = 0.002 s): cell 0 is at (nan, 0) m", 0),
      0u);
}

TEST(PowerlawOptions, RangesNamedBeforeAnyInputIsRead) {
  analysis::FitOptions opt;
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(opt); }), "(no error)");
  auto bad = opt;
  bad.significance = 2;
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(bad); }), "--significance: must lie in (0, 1), got 2");
  bad = opt;
  bad.threads = 100000;
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(bad); }).rfind("--threads: must lie in [0, ", 0), 0u);
  bad = opt;
  bad.bootstrap = 2000000000;
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(bad); }),
            "--bootstrap: must lie in [0, 1000000], got 2000000000");
  bad = opt;
  bad.bins_per_decade = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(bad); }), "--bins-per-decade: must lie in (0, 1000], got inf");
  bad = opt;
  bad.logbin_min = -1;
  EXPECT_EQ(error_of([&] { analysis::check_fit_options(bad); }),
            "--logbin-min: must be xmin, all or a number >= 0, got -1");
}

TEST(DemRun, AFrameIntervalBelowTheTimesResolutionTakesAFrameAStep) {
  // 1e-300 s between frames: one frame a step (and the final one), not a loop adding 1e-300 to 1e-6.
  const mesh::CellMesh m = block();
  dem::Simulation sim(m, dem_scene("explosion", {{"output.frame_interval", "1e-300"}, {"stop.max_steps", "12"}}));
  const fs::path path = fs::temp_directory_path() / ("fracture-test-frames-" + make_uuid().substr(0, 8) + ".h5");
  io::OutputFile out(path.string());
  io::write_header(out.root(), "run", start_run("test", "test"), out.uuid());
  io::RunWriter writer(out.root(), m, sim.model.bodies().mass, sim.model.bodies().inertia);
  Progress progress("test", true);
  dem::DemRun engine = sim.engine();
  const dem::RunSummary s = engine.summary(run::drive(engine, &writer, progress, io::Continuation{}));
  EXPECT_EQ(s.steps, 12);
  EXPECT_EQ(writer.frames(), 13u);
}
