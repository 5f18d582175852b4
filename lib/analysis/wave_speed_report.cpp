#include "analysis/wave_speed_report.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <sstream>

#include "analysis/wave_speed_theory.hpp"
#include "core/error.hpp"
#include "io/mesh_io.hpp"
#include "io/run_io.hpp"

namespace frac::analysis {
namespace {

// ---- where the runs record what wave-speed can use (/parameters/<tool>, "section.key") ----
// rubber-run (data/scenes/wave.ini, rubber/setup.cpp) and dem-run (data/scenes/pulse.ini). The first key
// present wins; kept in one place so that a renamed scene key is a one-line change.
const std::initializer_list<const char*> kKeyA = {"material.a"};
const std::initializer_list<const char*> kKeyB = {"material.b"};
const std::initializer_list<const char*> kKeyArealDensity = {"derived.areal_density"};  // rubber, kg/m^2
const std::initializer_list<const char*> kKeyDensity = {"material.density"};  // kg/m^3 (rubber: times thickness)
const std::initializer_list<const char*> kKeyThickness = {"material.thickness"};
const std::initializer_list<const char*> kKeyShortWidth = {"law.short_width", "material.short_width"};
const std::initializer_list<const char*> kKeyCutoff = {"law.cutoff_length", "material.cutoff_length"};
const std::initializer_list<const char*> kKeyCutoffWidth = {"law.cutoff_width", "material.cutoff_width"};
const std::initializer_list<const char*> kKeyCutoffKind = {"law.cutoff"};    // "none": no Fermi cut-off
const std::initializer_list<const char*> kKeyStretch = {"loading.stretch"};  // "1.5x3"
const std::initializer_list<const char*> kKeyStretchX = {"loading.stretch_x", "loading.lambda_x"};
const std::initializer_list<const char*> kKeyStretchY = {"loading.stretch_y", "loading.lambda_y"};
const std::initializer_list<const char*> kKeyLoadingKind = {"loading.kind"};
// The rubber wave scene's pulse: polarisation, direction (x | y), centre as a fraction of the mesh's
// reference extent along the direction, Gaussian width (reference m).
const std::initializer_list<const char*> kKeyPulseMode = {"pulse.kind"};
const std::initializer_list<const char*> kKeyPulseDirection = {"pulse.direction"};
const std::initializer_list<const char*> kKeyPulsePosition = {"pulse.position"};
const std::initializer_list<const char*> kKeyPulseWidth = {"pulse.width"};
// The lattice's own long-wave speeds at the run's cut-off (rubber-run derives them): "derived.lattice.c_T_x".
const char* kKeyLatticeSpeed = "derived.lattice.c_";
// How many pulse widths the initial pulse reaches: the automatic fit range starts beyond them.
constexpr double kNearFieldWidths = 3.0;

using Params = std::map<std::string, std::string>;
using Vec2 = Eigen::Vector2d;

struct Found {
  std::string key, value;
};
std::optional<Found> lookup(const Params& p, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (auto it = p.find(k); it != p.end()) return Found{k, it->second};
  return std::nullopt;
}

double to_number(const Found& f, const std::string& where) {
  std::istringstream in(f.value);
  double v = 0;
  in >> v;
  if (!in || !(in >> std::ws).eof()) throw InputError(where + " " + f.key + " = '" + f.value + "' is not a number");
  return v;
}

std::string number(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

herr_t collect_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

const char* kMrFormulas =
    "Mooney-Rivlin sheet W = rho a (J1 + b J2), F = diag(lambda_x, lambda_y), J = lambda_x lambda_y, lab direction "
    "n: c_T^2 = a (1 - b/2) |F^T n|^2, c_L^2 = a [(1 - b/2) |F^T n|^2 + (b/2) J^2] (lab speeds); reference-frame "
    "speeds omega/|k_ref| = lab / |F^T n|; P_xx = rho a lambda_x [1 + (b/2)(lambda_y^2 - 1)], P_yy = rho a "
    "lambda_y [1 + (b/2)(lambda_x^2 - 1)], sigma_xx = P_xx / lambda_y, sigma_yy = P_yy / lambda_x "
    "(physics/rubber-lattice.md section 4)";
const char* kPlaneStressFormulas =
    "isotropic linear-elastic plate in plane stress, Young modulus K, Poisson ratio nu, density rho (3D): "
    "c_L = sqrt(K / (rho (1 - nu^2))), c_S = sqrt(K / (2 rho (1 + nu))); the bar speed is sqrt(K / rho)";

bool isotropic(Stretch s) { return std::abs(s.x - s.y) <= 1e-9 * std::max(s.x, s.y); }

// Predictions for the given directions (labels unique). `skipped` names the directions with none.
io::SpeedsRecord predict(const TheoryInputs& in, std::vector<std::string>& skipped) {
  io::SpeedsRecord r;
  r.origin = "theory";
  std::vector<double> dirs = in.directions;
  if (dirs.empty()) dirs = {0.0, std::numbers::pi / 2};
  // One prediction per distinct direction label.
  std::vector<std::string> labels;
  for (double d : dirs)
    if (const std::string l = direction_label(d); std::find(labels.begin(), labels.end(), l) == labels.end())
      labels.push_back(l);
  if (in.theory == "dem") {
    if (!in.young || !in.poisson || !in.density)
      throw UsageError("--theory dem needs --young (Pa), --poisson and --density (kg/m^3)");
    const PlaneStressSpeeds s = plane_stress_speeds(*in.young, *in.poisson, *in.density);
    r.theory = "plane-stress";
    r.formulas = kPlaneStressFormulas;
    r.parameters = {{"young", *in.young, "Pa"}, {"poisson", *in.poisson, "1"}, {"density", *in.density, "kg m-3"}};
    for (std::size_t k = 0; k < labels.size(); ++k) {
      const double d = parse_direction(labels[k], "--direction");
      r.predicted.push_back({labels[k], d, s.longitudinal, s.shear, io::kNoValue, io::kNoValue});
    }
    return r;
  }
  if (in.theory != "mooney-rivlin")
    throw UsageError("--theory: expected mooney-rivlin or dem, got '" + in.theory + "'");
  if (!in.a || !in.b) throw UsageError("--theory mooney-rivlin needs --a (m^2/s^2) and --b");
  const Stretch st = in.stretch.value_or(Stretch{});
  MooneyRivlin m{*in.a, *in.b, in.density.value_or(1.0)};
  validate(m, st);
  r.theory = "mooney-rivlin";
  r.formulas = kMrFormulas;
  r.parameters = {{"a", m.a, "m2 s-2"}, {"b", m.b, "1"}};
  if (in.density) r.parameters.push_back({"density", *in.density, "kg m-2"});
  r.parameters.push_back({"stretch_x", st.x, "1"});
  r.parameters.push_back({"stretch_y", st.y, "1"});
  for (const auto& l : labels) {
    const double d = parse_direction(l, "--direction");
    if (is_radial(d) && !isotropic(st)) {
      skipped.push_back("radial (the stretched sheet is anisotropic)");
      continue;
    }
    // Radial in an isotropic sheet: the speeds of any direction.
    const MrWaveSpeeds s = mooney_rivlin_speeds(m, st, is_radial(d) ? 0.0 : d);
    r.predicted.push_back({l, d, s.longitudinal, s.shear, s.longitudinal_reference, s.shear_reference});
  }
  if (in.density) {
    const MrStress s = mooney_rivlin_stress(m, st);
    r.stress = {{"piola_xx", s.piola_xx, "N m-1"},
                {"piola_yy", s.piola_yy, "N m-1"},
                {"cauchy_xx", s.cauchy_xx, "N m-1"},
                {"cauchy_yy", s.cauchy_yy, "N m-1"}};
  }
  // The lattice check, when the lattice is described.
  if (in.spacing || in.short_width || in.cutoff || in.cutoff_width) {
    LatticeParameters lp;
    lp.spacing = in.spacing.value_or(0.0);
    lp.rows_along = in.rows_along.value_or("x");
    lp.short_width = in.short_width.value_or(-1.0);
    lp.cutoff = in.cutoff.value_or(-1.0);
    lp.cutoff_width = in.cutoff_width.value_or(-1.0);
    if (in.short_width && !in.spacing) throw UsageError("--short-width needs --spacing (the lattice spacing Delta)");
    const LatticeCheck c = check_lattice(lp, st);
    r.lattice_regime = std::string(name(c.regime));
    r.lattice_message = c.message;
    if (lp.spacing > 0)
      for (const auto& f : c.families) {
        r.bond_angle.push_back(f.reference_angle);
        r.bond_length.push_back(f.length);
      }
  }
  return r;
}

}  // namespace

std::map<std::string, std::string> run_parameters(const io::Group& run, std::string_view tool) {
  std::map<std::string, std::string> out;
  const std::string path = "parameters/" + std::string(tool);
  if (!run.has(path)) return out;
  const io::Group g = run.group(path);
  std::vector<std::string> names;
  hsize_t index = 0;
  if (H5Aiterate2(g.id(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_name, &names) < 0)
    throw InputError(g.where() + ": cannot list the attributes");
  for (const auto& n : names) {
    try {
      out[n] = g.attr_string(n);
    } catch (const InputError&) {
      // Not a string attribute: not a scene key.
    }
  }
  return out;
}

std::string parse_theory(std::string_view text, std::string_view option) {
  if (text == "mooney-rivlin" || text == "mr") return "mooney-rivlin";
  if (text == "dem") return "dem";
  throw UsageError(std::string(option) + ": expected mooney-rivlin or dem, got '" + std::string(text) + "'");
}

io::SpeedsRecord predict_speeds(const TheoryInputs& in) {
  TheoryInputs t = in;
  if (t.theory.empty()) t.theory = "mooney-rivlin";
  std::vector<std::string> skipped;
  io::SpeedsRecord r = predict(t, skipped);
  if (r.predicted.empty())
    throw UsageError("--direction: no prediction for " +
                     (skipped.empty() ? std::string("these directions") : skipped[0]));
  return r;
}
namespace {

// The run's recorded parameters, where they come from, and the notes saying which defaults were taken.
struct RunDefaults {
  const Params& params;
  std::string from;  // "/parameters/<tool>"
  std::vector<std::string>& notes;
  void note(const std::string& what, const Found& f) const {
    notes.push_back(what + " from " + from + " " + f.key + " = " + f.value);
  }
};

// Mode, direction, source and near field of the run's own pulse, where the user left them unset.
void apply_run_defaults(const io::Group& run, bool rubber, const RunDefaults& d, RunRequest& req) {
  const Params& params = d.params;
  const std::string& from = d.from;
  const auto kind = lookup(params, kKeyLoadingKind);
  const bool wave_scene = rubber && kind && kind->value == "wave";
  if (!req.modes_given && wave_scene) {
    if (const auto f = lookup(params, kKeyPulseMode)) {
      req.front.modes = {parse_wave_mode(f->value, from + " " + f->key)};
      d.note("mode", *f);
    }
  }
  std::optional<Found> pulse_direction = wave_scene ? lookup(params, kKeyPulseDirection) : std::nullopt;
  if (!req.directions_given) {
    if (pulse_direction) {
      req.front.directions = {parse_direction(pulse_direction->value, from + " " + pulse_direction->key)};
      d.note("direction", *pulse_direction);
    } else if (!rubber && kind && (kind->value == "pulse" || kind->value == "explosion")) {
      req.front.directions = {kRadial};
      d.note("direction radial (a point source)", *kind);
    } else {
      req.front.directions = {0.0};
    }
  }
  if (wave_scene && !req.front.source && pulse_direction) {
    // The pulse sits on the line s = lo + position (hi - lo) of the reference mesh across its direction.
    if (const auto f = lookup(params, kKeyPulsePosition)) {
      const double fraction = to_number(*f, from);
      const mesh::NodeMesh mesh = io::read_node_mesh(run);
      Vec2 lo = mesh.position.front(), hi = lo;
      for (const auto& p : mesh.position) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      Vec2 centre = 0.5 * (lo + hi);
      const int axis = pulse_direction->value == "y" ? 1 : 0;
      centre(axis) = lo(axis) + fraction * (hi(axis) - lo(axis));
      req.front.source_reference = centre;
      d.note("source (mapped by the first frame's stretch)", *f);
    }
  }
  if (wave_scene && !std::isfinite(req.front.s_min))
    if (const auto f = lookup(params, kKeyPulseWidth)) req.front.near_field = kNearFieldWidths * to_number(*f, from);
}

// The measurement as a record (origin "run"). InputError when a mode the user asked for, or every front,
// could not be timed; other failures become notes.
io::SpeedsRecord measured_record(const io::Group& run, const WaveMeasurement& m, const RunRequest& req,
                                 std::vector<std::string>& notes) {
  io::SpeedsRecord r;
  r.origin = "run";
  r.model = m.model;
  r.signal = std::string(name(m.signal));
  r.arrival = std::string(name(req.front.arrival));
  r.amplitude = std::string(name(req.front.amplitude));
  r.threshold = req.front.threshold;
  r.source = {m.source.x(), m.source.y()};
  r.source_from = m.source_from == "reference" ? "parameters" : m.source_from;
  r.frame_interval = m.frame_interval;
  r.frames = static_cast<std::int64_t>(m.frames);
  r.bin = m.bin;
  r.deformation = {m.deformation(0, 0), m.deformation(0, 1), m.deformation(1, 0), m.deformation(1, 1)};
  for (const FrontMeasurement& f : m.fronts) {
    io::MeasuredSpeed x;
    x.mode = std::string(name(f.mode));
    x.label = x.mode + "." + direction_label(f.direction);
    x.direction = f.direction;
    x.ok = f.ok;
    x.failure = f.failure;
    x.speed = f.speed;
    x.speed_stderr = f.speed_stderr;
    x.intercept = f.fit.intercept;
    x.residual_rms = f.fit.residual_rms;
    x.frame_bound = f.frame_bound;
    x.points = static_cast<std::int64_t>(f.fit.points);
    x.rejected = static_cast<std::int64_t>(f.fit.rejected);
    x.range_min = f.s_min;
    x.range_max = f.s_max;
    x.distance = f.distance;
    x.arrival = f.arrival;
    x.amplitude = f.amplitude;
    x.used = f.used;
    if (x.used.size() != x.distance.size()) x.used.assign(x.distance.size(), 0);
    if (!f.ok) {
      // A mode asked for on the command line must be measured; one taken from the run or chosen
      // automatically is only noted.
      if (req.modes_given && !req.front.modes.empty()) throw InputError(run.file() + ": " + f.failure);
      notes.push_back("not measured: " + f.failure);
    }
    r.measured.push_back(std::move(x));
  }
  if (std::none_of(m.fronts.begin(), m.fronts.end(), [](const FrontMeasurement& f) { return f.ok; }))
    throw InputError(
        run.file() + ": no front could be timed" +
        (m.fronts.empty() ? std::string(" (no signal in the distance range)") : ": " + m.fronts[0].failure));
  return r;
}

// The Mooney-Rivlin inputs the user left unset, from the rubber run: material, density, lattice, stretch.
void rubber_theory_inputs(const io::Group& run, const RunDefaults& d, const RunRequest& req, const WaveMeasurement& m,
                          TheoryInputs& th) {
  const Params& params = d.params;
  const std::string& from = d.from;
  const auto fill = [&](std::optional<double>& v, std::initializer_list<const char*> keys, const char* what) {
    if (v) return;
    if (const auto f = lookup(params, keys)) {
      v = to_number(*f, from);
      d.note(what, *f);
    }
  };
  fill(th.a, kKeyA, "a");
  fill(th.b, kKeyB, "b");
  if (!th.density) {
    if (const auto f = lookup(params, kKeyArealDensity)) {
      th.density = to_number(*f, from);
      d.note("areal density", *f);
    } else if (const auto density = lookup(params, kKeyDensity), t = lookup(params, kKeyThickness); density && t) {
      th.density = to_number(*density, from) * to_number(*t, from);
      d.note("areal density = density x thickness", *density);
    }
  }
  fill(th.short_width, kKeyShortWidth, "short-bond width u_s");
  fill(th.cutoff, kKeyCutoff, "cut-off u_c");
  fill(th.cutoff_width, kKeyCutoffWidth, "cut-off width");
  if (const auto f = lookup(params, kKeyCutoffKind); f && f->value == "none" && !req.theory.cutoff_width)
    th.cutoff_width = 0.0;  // h = 1: nothing stiffens the far field before u_c
  if (!th.spacing && run.has_attr("spacing", "particles/nodes"))
    th.spacing = run.attr_double("spacing", "particles/nodes");
  if (!th.rows_along && run.has_attr("rows_along", "particles/nodes"))
    th.rows_along = run.attr_string("rows_along", "particles/nodes");
  if (!th.stretch) {
    if (const auto f = lookup(params, kKeyStretch)) {
      const auto x = f->value.find_first_of("xX");
      if (x != std::string::npos) {
        th.stretch = Stretch{to_number({f->key, f->value.substr(0, x)}, from),
                             to_number({f->key, f->value.substr(x + 1)}, from)};
        d.note("stretch", *f);
      }
    }
  }
  if (!th.stretch) {
    const auto fx = lookup(params, kKeyStretchX), fy = lookup(params, kKeyStretchY);
    if (fx && fy) {
      th.stretch = Stretch{to_number(*fx, from), to_number(*fy, from)};
      d.note("stretch_x", *fx);
      d.note("stretch_y", *fy);
    }
  }
  if (!th.stretch) {
    const auto& F = m.deformation;
    th.stretch = Stretch{F(0, 0), F(1, 1)};
    const double shear = std::max(std::abs(F(0, 1)), std::abs(F(1, 0)));
    d.notes.push_back("stretch " + number(F(0, 0)) + "x" + number(F(1, 1)) +
                      " from the first frame (least-squares deformation of the links)" +
                      (shear > 1e-3 * std::max(F(0, 0), F(1, 1))
                           ? "; it is not diagonal (off-diagonal " + number(shear) + "): give --stretch"
                           : ""));
  }
  if (th.theory.empty() && th.a && th.b) th.theory = "mooney-rivlin";
}

// The DEM's density, when the user left it unset; plane stress when K, nu and rho are all known.
void dem_theory_inputs(const RunDefaults& d, TheoryInputs& th) {
  if (!th.density)
    if (const auto f = lookup(d.params, kKeyDensity)) {
      th.density = to_number(*f, d.from);
      d.note("density", *f);
    }
  if (th.theory.empty() && th.young && th.poisson && th.density) th.theory = "dem";
}

// Each measured speed against the prediction for its mode and direction, and (rubber) against the lattice's
// own long-wave speed when the run derived it.
void compare_speeds(io::SpeedsRecord& r, bool rubber, const RunDefaults& d) {
  for (auto& x : r.measured) {
    if (!x.ok) continue;
    for (const auto& q : r.predicted) {
      if (x.label != x.mode + "." + q.label) continue;
      x.predicted = x.mode == "longitudinal" ? q.longitudinal : q.shear;
      x.deviation = x.speed / x.predicted - 1;
    }
    // The lattice's own long-wave speed at the run's cut-off, when the run derived it (along x and y).
    const std::string axis = direction_label(x.direction);
    if (rubber && (axis == "x" || axis == "y" || axis == "-x" || axis == "-y")) {
      const std::string key = std::string(kKeyLatticeSpeed) + (x.mode == "longitudinal" ? "L_" : "T_") + axis.back();
      if (auto it = d.params.find(key); it != d.params.end()) {
        x.lattice_predicted = to_number({key, it->second}, d.from);
        x.lattice_deviation = x.speed / x.lattice_predicted - 1;
      }
    }
  }
}

}  // namespace

io::SpeedsRecord measure_and_compare(const io::Group& run, RunRequest req, std::vector<std::string>& notes) {
  const io::RunInfo info = io::read_run_info(run);
  const bool rubber = info.model == "rubber";
  const std::string tool = rubber ? "rubber-run" : "dem-run";
  const Params params = run_parameters(run, tool);
  const RunDefaults d{params, "/parameters/" + tool, notes};

  apply_run_defaults(run, rubber, d, req);
  const WaveMeasurement m = measure_wave_speeds(run, req.front);
  io::SpeedsRecord r = measured_record(run, m, req, notes);

  // ---- the prediction for the same material and stretch ----
  TheoryInputs th = req.theory;
  th.directions.clear();
  for (const auto& f : m.fronts) th.directions.push_back(f.direction);
  if (rubber)
    rubber_theory_inputs(run, d, req, m, th);
  else
    dem_theory_inputs(d, th);

  if (th.theory.empty()) {
    r.comparison =
        rubber ? "not compared: no prediction (give --a and --b, or a run that records material.a and material.b)"
               : "not compared: no prediction (give --young and --poisson measured on the DEM, and --density)";
    return r;
  }
  if (th.theory == "mooney-rivlin" && !rubber)
    throw UsageError("--theory mooney-rivlin describes the rubber lattice; this run is a DEM run (use --theory dem)");
  if (th.theory == "dem" && rubber)
    throw UsageError("--theory dem describes the polygon DEM; this run is a rubber run (use --theory mooney-rivlin)");
  std::vector<std::string> skipped;
  io::SpeedsRecord p = predict(th, skipped);
  for (const auto& s : skipped) notes.push_back("no prediction along " + s);
  r.theory = p.theory;
  r.formulas = p.formulas;
  r.parameters = p.parameters;
  r.predicted = p.predicted;
  r.stress = p.stress;
  r.lattice_regime = p.lattice_regime;
  r.lattice_message = p.lattice_message;
  r.bond_angle = p.bond_angle;
  r.bond_length = p.bond_length;

  if (!r.lattice_regime.empty() && r.lattice_regime != "mooney-rivlin" && r.lattice_regime != "unchecked") {
    r.comparison = "not compared: " + r.lattice_message;
    return r;
  }
  compare_speeds(r, rubber, d);
  r.comparison =
      r.lattice_regime == "unchecked" ? "compared (lattice not checked: " + r.lattice_message + ")" : "compared";
  return r;
}

}  // namespace frac::analysis
