#include "rubber/setup.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>
#include <variant>

#include "core/error.hpp"
#include "core/physical_limits.hpp"
#include "rubber/frames.hpp"

namespace frac::rubber {
namespace {
// The three-body weight h at which irreversible breaking may remove a bond without a visible energy jump:
// the jump is about h times the bond's share of the three-body energy.
constexpr double kBreakingWeightLimit = 1e-3;

std::string num(double x, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

// "3.4e-3 m (3.4Δ)"
std::string len(double x, double spacing) { return num(x, 5) + " m (" + num(x / spacing, 4) + "Δ)"; }

}  // namespace

void require_run_keys(const Scene& s) { s.require("loading.kind", "what the run does: stretch or wave"); }

namespace {

// The sheet's extent along x and its largest extent, for lengths that must fit on it.
std::pair<double, double> sheet_length_and_size(const mesh::NodeMesh& mesh) {
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  for (std::size_t i = 0; i < mesh.position.size(); ++i) {
    const auto& p = mesh.position[i];
    xmin = i ? std::min(xmin, p.x()) : p.x(), xmax = i ? std::max(xmax, p.x()) : p.x();
    ymin = i ? std::min(ymin, p.y()) : p.y(), ymax = i ? std::max(ymax, p.y()) : p.y();
  }
  return {xmax - xmin, std::max(xmax - xmin, ymax - ymin)};
}

// material.* and law.*: the continuum constants and the bond law on lattice spacing d.
void read_material_and_law(Scene& s, RubberScene& r, double d) {
  using limits::kSpeed;
  const Interval law_length = Interval::open_closed(0, 1e3 * d);
  r.density = s.in("material.density", r.density, Interval::open_closed(0, limits::kDensity));
  r.thickness = s.in("material.thickness", r.thickness, Interval::open_closed(0, limits::kThickness));
  r.a = s.in("material.a", r.a, Interval::open_closed(0, kSpeed * kSpeed));  // a = c^2
  r.b = s.in("material.b", r.b, Interval::closed(0, 1e3));

  r.pair = s.choice("law.pair", r.pair, pair_law_names());
  r.cutoff = s.choice("law.cutoff", r.cutoff, cutoff_law_names());
  r.angle = s.choice("law.angle", r.angle, angle_law_names());
  r.three_body_weight = s.choice("law.three_body_weight", r.three_body_weight, three_body_weight_names());
  r.three_body_residual = s.non_negative("law.three_body_residual", 0.0);
  if (!(r.three_body_residual < 1))
    throw UsageError(s.name() +
                     ": law.three_body_residual must lie in [0, 1) (the fraction of the far-field three-body "
                     "energy a failed pair keeps)");
  r.failure = s.choice("law.failure", r.failure, {"paper", "freeze"});
  r.short_width = s.in("law.short_width", 0.1 * d, law_length);
  r.cutoff_length = s.in("law.cutoff_length", 3.5 * d, law_length);
  r.cutoff_width = s.in("law.cutoff_width", 0.05 * d, law_length);
  if (!(r.cutoff_length > d + r.short_width))
    throw UsageError(s.name() + ": law.cutoff_length = " + num(r.cutoff_length) + " m must exceed the spacing plus " +
                     "law.short_width (" + num(d + r.short_width) + " m)");
}

// physics.* switches and the damping, breaking and toughening they switch on; tau: the time unit Δ/√a.
void read_physics(Scene& s, RubberScene& r, double d, double tau) {
  r.damping = s.flag("physics.damping", r.damping);
  r.irreversible = s.flag("physics.irreversible", r.irreversible);
  r.toughening = s.flag("physics.toughening", r.toughening);
  const std::string kind = s.choice("damping.kind", "uniform", {"uniform", "near_failure"});
  r.damping_kind = kind == "uniform" ? DampingKind::uniform : DampingKind::near_failure;
  const double mass = mr::node_mass(r.density * r.thickness, d);
  r.beta = s.non_negative("damping.beta", 0.3 * mass / tau);
  r.damping_onset = s.positive("damping.onset", r.cutoff_length - 10 * r.cutoff_width);
  if (r.damping && r.damping_kind == DampingKind::near_failure && !(r.damping_onset < r.cutoff_length))
    throw UsageError(s.name() + ": damping.onset must lie below law.cutoff_length");
  r.break_widths = s.positive("breaking.extra_widths", r.break_widths);
  r.toughening_trigger = s.positive("toughening.trigger", 1.5 * d);
  r.toughening_cutoff = s.positive("toughening.cutoff", r.cutoff_length + 10 * r.cutoff_width);
  if (!(r.toughening_cutoff > r.cutoff_length))
    throw UsageError(s.name() + ": toughening.cutoff must exceed law.cutoff_length");
  r.toughening_every = s.integer("toughening.every", r.toughening_every);
  if (r.toughening_every <= 0) throw UsageError(s.name() + ": toughening.every must be positive");
}

// loading.*, boundary.* and crack.*: what is done to the sheet of the given length along x.
void read_loading(Scene& s, RubberScene& r, const mesh::NodeMesh& mesh, double length) {
  using limits::kSpeed, limits::kStretch;
  r.kind = s.choice("loading.kind", r.kind, {"stretch", "wave"});
  r.stretch_x = s.in("loading.stretch_x", r.stretch_x, Interval::open_closed(0, kStretch));
  r.stretch_y = s.in("loading.stretch_y", r.stretch_y, Interval::open_closed(0, kStretch));

  r.clamp_rows = s.integer("boundary.clamp_rows", r.kind == "stretch" ? 2 : 0);
  r.clamp_columns = s.integer("boundary.clamp_columns", 0);
  if (r.clamp_rows < 0 || r.clamp_columns < 0) throw UsageError(s.name() + ": boundary clamps must not be negative");
  if (2 * r.clamp_rows >= mesh.ny && r.clamp_rows > 0)
    throw UsageError(s.name() + ": boundary.clamp_rows = " + std::to_string(r.clamp_rows) + " clamps the whole mesh (" +
                     std::to_string(mesh.ny) + " rows)");
  if (2 * r.clamp_columns >= mesh.nx && r.clamp_columns > 0)
    throw UsageError(s.name() + ": boundary.clamp_columns = " + std::to_string(r.clamp_columns) +
                     " clamps the whole mesh (" + std::to_string(mesh.nx) + " columns)");
  const std::string periodic = s.choice("boundary.periodic", "none", {"none", "x", "y", "xy"});
  r.periodic_x = periodic == "x" || periodic == "xy";
  r.periodic_y = periodic == "y" || periodic == "xy";
  if (r.periodic_y && r.clamp_rows > 0)
    throw UsageError(s.name() + ": boundary.periodic = " + periodic + " leaves no top and bottom rows to clamp");
  if (r.periodic_x && r.clamp_columns > 0)
    throw UsageError(s.name() + ": boundary.periodic = " + periodic + " leaves no side columns to clamp");
  // Stretching with the seed in place: the sheet starts at (λx, ramp_from_y), the whole sheet moving at the
  // homogeneous stretch rate, and the clamped rows reach stretch_y at ramp_time, then stay.
  r.ramp_time = s.non_negative("loading.ramp_time", 0.0);
  r.ramp_from_y = s.in("loading.ramp_from_y", r.stretch_y, Interval::open_closed(0, kStretch));
  if (r.ramp_time > 0 && (r.clamp_rows == 0 || r.periodic_y))
    throw UsageError(s.name() + ": loading.ramp_time needs clamped top and bottom rows (boundary.clamp_rows)");

  r.seed_length = s.non_negative("crack.seed_length", 0.0);  // (no longer than the crack line: build_rubber)
  r.tip_kick = s.in("crack.tip_kick", 0.0, Interval::closed(0, kSpeed));
  r.path_cutoff_ratio = s.positive("crack.path_cutoff_ratio", r.path_cutoff_ratio);
  if (r.path_cutoff_ratio < 1)
    throw UsageError(s.name() + ": crack.path_cutoff_ratio = " + num(r.path_cutoff_ratio) +
                     " must be at least 1 (the bulk's cut-off over the crack path's: the path is the weak plane)");
  r.drive_speed = s.in("crack.drive_speed", 0.0, Interval::closed(0, kSpeed));
  r.drive_length = s.in("crack.drive_length", 0.0, Interval::closed(0, length));
  if ((r.drive_speed > 0) != (r.drive_length > 0))
    throw UsageError(s.name() +
                     ": crack.drive_speed and crack.drive_length go together (both positive: the driven "
                     "seed; both 0: off)");
}

// pulse.*, initial.*, integrator.*, stop.* and output.*.
void read_pulse_and_run(Scene& s, RubberScene& r, double d, double tau, double size) {
  using limits::kSpeed;
  const Interval on_sheet = Interval::closed(0, size);
  r.pulse_kind = s.choice("pulse.kind", r.pulse_kind, {"longitudinal", "shear"});
  r.pulse_direction = s.choice("pulse.direction", r.pulse_direction, {"x", "y"});
  r.pulse_amplitude = s.in("pulse.amplitude", r.kind == "wave" ? 0.01 * d : 0.0, on_sheet);
  r.pulse_width = s.positive("pulse.width", 10 * d);
  r.pulse_position = s.number("pulse.position", 0.5);
  if (r.pulse_position < 0 || r.pulse_position > 1) throw UsageError(s.name() + ": pulse.position must lie in [0, 1]");

  r.noise = s.in("initial.noise", 0.0, Interval::closed(0, kSpeed));

  r.integrator = dynamics::parse_integrator_kind(s.text("integrator.kind", "verlet"), "integrator.kind");
  r.t_max = s.positive("stop.t_max", 100 * tau);
  r.dt = dynamics::read_time_step(s, r.t_max);
  r.safety = s.positive("integrator.safety", r.safety);
  if (r.safety > 1) throw UsageError(s.name() + ": integrator.safety must not exceed 1");
  r.allow_unstable = s.flag("integrator.allow_unstable", r.allow_unstable);

  r.max_steps = s.integer("stop.max_steps", r.max_steps);
  if (r.max_steps <= 0) throw UsageError(s.name() + ": stop.max_steps must be positive");
  r.tip_margin = s.non_negative("stop.tip_margin", 0.0);

  r.frame_interval = s.non_negative("output.frame_interval", r.t_max / 20);
  r.observe_every = s.integer("output.observe_every", r.observe_every);
  if (r.observe_every <= 0) throw UsageError(s.name() + ": output.observe_every must be positive");
  r.frames = s.subset("output.frames", frame_names());
  if (r.frames.empty() || r.frames.front() != "position")
    s.refuse("output.frames", "must name position: the readers of a run find its frames by it");
  r.speed_window = s.positive("output.speed_window", 20 * tau);
}

}  // namespace

RubberScene read_rubber_scene(Scene& s, const mesh::NodeMesh& mesh) {
  RubberScene r;
  const double d = mesh.spacing;
  if (!(d > 0)) throw InputError("the mesh has no lattice spacing");
  const auto [length, size] = sheet_length_and_size(mesh);
  read_material_and_law(s, r, d);
  const double tau = d / std::sqrt(r.a);  // the natural time unit Δ/√a
  read_physics(s, r, d, tau);
  read_loading(s, r, mesh, length);
  read_pulse_and_run(s, r, d, tau, size);
  return r;
}

std::vector<std::string> far_field_warnings(const RubberSetup& su) {
  std::vector<std::string> w;
  const RubberScene& sc = su.scene;
  const double d = su.spacing, knee = d + sc.short_width;
  const std::string at = "at stretch (" + num(sc.stretch_x) + ", " + num(sc.stretch_y) + ")";
  double u0 = 0;
  int longest = 0;
  for (int f = 0; f < 3; ++f) {
    const double u = su.family_length[f];
    if (u > u0) {
      u0 = u;
      longest = f;
    }
    if (u < knee) {
      w.push_back("the bonds at " + num(su.family_angle[f]) + " degrees are " + len(u, d) + " long " + at +
                  ", shorter than spacing + law.short_width = " + len(knee, d) +
                  ": the lattice is not Mooney-Rivlin there (short-bond branch of f; physics/rubber-lattice.md §4)" +
                  (su.family_angle[0] == 0
                       ? "; a mesh with close-packed rows along y (mesh-gen triangular --rows-along y) may avoid it"
                       : "; a mesh with close-packed rows along x may avoid it"));
    }
  }
  if (sc.cutoff != "none") {
    const double widths = (sc.cutoff_length - u0) / sc.cutoff_width;
    const double deficit = 1 - std::visit([&](const auto& h) { return h(u0, sc.cutoff_length).v; }, su.law.cutoff);
    auto speed = [](double c) { return std::isnan(c) ? std::string("unstable") : num(c, 4) + " m/s"; };
    const std::string speeds = "the lattice's long-wave speeds along x are c_T = " + speed(su.lattice_x.transverse) +
                               ", c_L = " + speed(su.lattice_x.longitudinal) + " against Mooney-Rivlin " +
                               speed(su.mr_x.transverse) + ", " + speed(su.mr_x.longitudinal);
    const std::string where = " of the bonds at " + num(su.family_angle[longest]) + " degrees " + at;
    std::string msg;
    if (sc.cutoff == "fermi" && widths < 15) {
      msg = "law.cutoff_length u_c = " + len(sc.cutoff_length, d) + " is " + num(widths, 3) +
            " cut-off widths (law.cutoff_width = " + len(sc.cutoff_width, d) +
            ") above the far-field bond length u_0 = " + len(u0, d) + where +
            "; below 15 widths the cut-off stiffens the far field (rubber-lattice-validation.md §D.1): " + speeds +
            "; raise u_c to at least u_0 + 15 widths = " + len(u0 + 15 * sc.cutoff_width, d) + " or narrow the cut-off";
    } else if (sc.cutoff != "fermi" && deficit > 1e-12) {
      msg = "the " + sc.cutoff + " cut-off reaches the far-field bonds: h(u_0) = " + num(1 - deficit, 6) +
            " at u_0 = " + len(u0, d) + where +
            " (it acts from u_c - width = " + len(sc.cutoff_length - sc.cutoff_width, d) +
            "), which changes the far field's stiffness: " + speeds +
            "; raise u_c to at least u_0 + width = " + len(u0 + sc.cutoff_width, d);
    }
    if (!msg.empty()) {
      if (u0 >= sc.cutoff_length)
        msg = "the far-field bonds (" + len(u0, d) + ") are past the cut-off u_c = " + len(sc.cutoff_length, d) +
              ": the pre-stretched sheet has no cohesion; " + msg;
      w.push_back(msg);
    }
  }
  return w;
}

namespace {

// Stability: the stiffest of three states a run meets: the stretched far field, the relaxed lattice
// (crack faces, free edges; branch 1 of f is stiff, ω ∝ √(Δ/u_s)), and bonds passing through the
// cut-off, where h'' ∝ 1/w² multiplies the large three-body energy (probed with the longest family at
// several points of the cut-off region; about 10 times the far field for a Fermi width of 0.05Δ). Sets
// omega_max, dt_bound and dt (the scene's, or safety · dt_bound).
void find_time_step(RubberSetup& su, const LawParams& p, bool rows_x) {
  const RubberScene& sc = su.scene;
  su.omega_far = omega_max(su.law, su.node_mass, su.F, rows_x);
  su.omega_relaxed = omega_max(su.law, su.node_mass, Eigen::Matrix2d::Identity(), rows_x);
  if (sc.cutoff != "none") {
    // Scan the cut-off region: the curvature of h peaks at u_c − 1.32 w for the Fermi function, at
    // u_c − 0.21 L and u_c − 0.79 L for the smoothstep.
    // With toughening or a crack path, bonds also pass through the raised cut-off, where g is larger still.
    const double u0 = std::max({su.family_length[0], su.family_length[1], su.family_length[2]});
    std::vector<std::pair<double, BondLaw>> cutoffs = {{sc.cutoff_length, su.law}};
    std::vector<double> raised;
    if (sc.toughening) raised.push_back(sc.toughening_cutoff);
    if (sc.path_cutoff_ratio != 1) raised.push_back(sc.path_cutoff_ratio * sc.cutoff_length);
    for (double uc : raised) {
      LawParams tp = p;
      tp.cutoff = uc;
      cutoffs.emplace_back(uc, make_bond_law(tp, sc.pair, sc.cutoff, sc.angle, sc.three_body_weight));
    }
    for (const auto& [uc, law] : cutoffs)
      for (double k : {0.21, 0.5, 0.79, 1.0, 1.32}) {
        const double scale = (uc - k * sc.cutoff_width) / u0;
        su.omega_cutoff = std::max(su.omega_cutoff, omega_max(law, su.node_mass, scale * su.F, rows_x));
      }
  }
  su.omega_max = std::max({su.omega_far, su.omega_relaxed, su.omega_cutoff});
  su.dt_bound = dynamics::stability_limit(sc.integrator) / su.omega_max;
  su.dt = sc.dt > 0 ? sc.dt : sc.safety * su.dt_bound;
  if (sc.dt > su.dt_bound && !sc.allow_unstable) {
    throw UsageError("integrator.dt = " + num(sc.dt) + " s is above the stability bound " + num(su.dt_bound) +
                     " s of " + std::string(dynamics::name(sc.integrator)) + " (omega_max = " + num(su.omega_max) +
                     " rad/s, the stiffest of the stretched far field, the relaxed lattice and a bond passing through "
                     "the cut-off); lower it, use auto, "
                     "or insist with --integrator.allow_unstable on");
  }
}

// The warnings of the failure law: energy jumps of irreversible breaking, the cohesive share of freezing.
void append_failure_warnings(RubberSetup& su) {
  const RubberScene& sc = su.scene;
  // An irreversibly broken bond leaves with its three-body terms, weighted by h where it is cut: cut
  // mid-cut-off, it takes that share of them at once and the energy jumps (2-4 % in the crack runs with
  // b = 0.02-0.25, a Fermi cut-off and 0.2 widths; docs/rubber-run.md).
  if (sc.irreversible && sc.failure == "paper" && sc.b != 0 && sc.cutoff != "none") {
    const double cut = sc.cutoff_length + sc.break_widths * sc.cutoff_width;
    const double h = std::visit([&](const auto& hc) { return hc(cut, sc.cutoff_length).v; }, su.law.cutoff);
    if (h > kBreakingWeightLimit)
      su.warnings.push_back("breaking.extra_widths = " + num(sc.break_widths) +
                            ": irreversible breaking removes a bond at u_c + " + num(sc.break_widths) +
                            " cut-off widths, where its three-body weight h is still " + num(h, 3) +
                            " (material.b = " + num(sc.b) +
                            "): the energy of its three-body terms goes at once and the total energy jumps; "
                            "raise breaking.extra_widths until h there is below " +
                            num(kBreakingWeightLimit));
  }
  // Energy-neutral failure freezes the terms at u_c with the weight h(u_c) they still have; the share the
  // cut-off released on the way is a cohesive barrier all the same.
  if (sc.failure == "freeze" && sc.cutoff != "none" && sc.b != 0) {
    const double h =
        std::visit([&](const auto& hc) { return hc(sc.cutoff_length, sc.cutoff_length).v; }, su.law.cutoff);
    su.warnings.push_back("law.failure = freeze with the " + sc.cutoff +
                          " cut-off: a bond fails at u_c, where h = " + num(h, 3) + ", so " + num(100 * (1 - h), 3) +
                          "% of its three-body share is released through h before it fails (a cohesive barrier), "
                          "not frozen; law.cutoff = none freezes all of it");
  }
  if (sc.b >= 2)
    su.warnings.push_back("material.b = " + num(sc.b) + ": Mooney-Rivlin has no real shear waves for b >= 2");
  if (sc.dt > su.dt_bound)
    su.warnings.push_back("integrator.dt = " + num(sc.dt) + " s is above the stability bound " + num(su.dt_bound) +
                          " s (allowed by integrator.allow_unstable)");
}

}  // namespace

RubberSetup prepare_rubber(const RubberScene& sc, const mesh::NodeMesh& mesh) {
  RubberSetup su;
  su.scene = sc;
  su.spacing = mesh.spacing;
  const double d = su.spacing;
  su.rho = sc.density * sc.thickness;
  su.node_mass = mr::node_mass(su.rho, d);
  LawParams p;
  p.spacing = d;
  p.A = mr::lattice_A(su.node_mass, sc.a, d);
  p.B = mr::lattice_B(su.node_mass, sc.a, sc.b, d);
  p.short_width = sc.short_width;
  p.cutoff = sc.cutoff_length;
  p.cutoff_width = sc.cutoff_width;
  su.law = make_bond_law(p, sc.pair, sc.cutoff, sc.angle, sc.three_body_weight);
  su.F = Eigen::Matrix2d{{sc.stretch_x, 0}, {0, sc.stretch_y}};
  const bool rows_x = mesh.rows_along != "y";
  for (int f = 0; f < 3; ++f) {
    const double th = (rows_x ? 0.0 : 30.0) + 60.0 * f;
    su.family_angle[f] = th;
    const double r = th * std::numbers::pi / 180;
    su.family_length[f] = (su.F * Eigen::Vector2d(std::cos(r), std::sin(r))).norm() * d;
  }

  find_time_step(su, p, rows_x);
  su.mr_x = mr::speeds_x(sc.stretch_x, sc.stretch_y, sc.a, sc.b);
  su.mr_y = mr::speeds_y(sc.stretch_x, sc.stretch_y, sc.a, sc.b);
  su.lattice_x = lattice_speeds(su.law, su.node_mass, sc.stretch_x, sc.stretch_y, 'x', rows_x);
  su.lattice_y = lattice_speeds(su.law, su.node_mass, sc.stretch_x, sc.stretch_y, 'y', rows_x);
  su.warnings = far_field_warnings(su);
  append_failure_warnings(su);
  return su;
}

std::vector<std::pair<std::string, std::string>> RubberSetup::derived() const {
  std::vector<std::pair<std::string, std::string>> d;
  auto add = [&d](const std::string& k, double v) { d.emplace_back("derived." + k, num(v, 10)); };
  add("spacing", spacing);
  add("node_mass", node_mass);
  add("areal_density", rho);
  add("A", law.params.A);
  add("B", law.params.B);
  for (int f = 0; f < 3; ++f) add("bond_length_" + num(family_angle[f]) + "deg", family_length[f]);
  add("omega_max", omega_max);
  add("omega_max_far_field", omega_far);
  add("omega_max_relaxed", omega_relaxed);
  add("omega_max_cutoff", omega_cutoff);
  add("dt_bound", dt_bound);
  add("dt", dt);
  add("time_unit", spacing / std::sqrt(scene.a));
  add("mooney_rivlin.c_T_x", mr_x.transverse);
  add("mooney_rivlin.c_L_x", mr_x.longitudinal);
  add("mooney_rivlin.c_T_y", mr_y.transverse);
  add("mooney_rivlin.c_L_y", mr_y.longitudinal);
  add("lattice.c_T_x", lattice_x.transverse);
  add("lattice.c_L_x", lattice_x.longitudinal);
  add("lattice.c_T_y", lattice_y.transverse);
  add("lattice.c_L_y", lattice_y.longitudinal);
  std::string all;
  for (const auto& w : warnings) all += (all.empty() ? "" : "\n") + w;
  d.emplace_back("derived.warnings", all);
  return d;
}

}  // namespace frac::rubber
