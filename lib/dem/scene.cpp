#include "dem/scene.hpp"

#include "core/error.hpp"
#include "core/physical_limits.hpp"

namespace frac::dem {

void require_run_keys(const Scene& s) {
  s.require("loading.kind", "what the run does: none, uniaxial, confined-compression, explosion, impact or pulse");
}

DemScene read_dem_scene(Scene& s) {
  DemScene d;
  d.material = read_material(s);
  d.physics = read_physics(s);
  Loading& l = d.loading;
  l.name = s.choice("loading.kind", "none",
                    {"none", "uniaxial", "confined-compression", "explosion", "impact", "pulse"});
  l.kind = l.name == "uniaxial"               ? LoadingKind::uniaxial
           : l.name == "confined-compression" ? LoadingKind::confined_compression
           : l.name == "explosion"            ? LoadingKind::explosion
           : l.name == "impact"               ? LoadingKind::impact
           : l.name == "pulse"                ? LoadingKind::pulse
                                              : LoadingKind::none;
  if (l.kind == LoadingKind::uniaxial || l.kind == LoadingKind::confined_compression) {
    const std::string fallback = l.kind == LoadingKind::uniaxial ? "tension" : "compression";
    l.tension = s.choice("loading.direction", fallback, {"tension", "compression"}) == "tension";
    l.boundary_speed = s.in("loading.boundary_speed", l.boundary_speed, Interval::open_closed(0, limits::kSpeed));
    l.ramp = s.positive("loading.ramp", l.ramp);
    l.layer_depth = s.non_negative("loading.layer_depth", l.layer_depth);
  }
  if (l.kind == LoadingKind::explosion || l.kind == LoadingKind::pulse)
    l.energy = s.positive("loading.energy", l.energy);
  if (l.kind == LoadingKind::impact) {
    l.impact_speed = s.in("loading.impact_speed", l.impact_speed, Interval::open_closed(0, limits::kSpeed));
    l.impact_energy = s.non_negative("loading.impact_energy", l.impact_energy);
    l.impact_width = s.non_negative("loading.impact_width", l.impact_width);
    l.layer_depth = s.non_negative("loading.layer_depth", l.layer_depth);
  }
  IntegratorSettings& in = d.integrator;
  in.kind = dynamics::parse_integrator_kind(s.text("integrator.kind", "gear5"), "integrator.kind");
  in.start = dynamics::parse_start_kind(s.choice("integrator.start", "zero", {"zero", "exact"}), "integrator.start");
  d.stop.t_max = s.positive("stop.t_max", d.stop.t_max);
  in.dt = dynamics::read_time_step(s, d.stop.t_max);
  in.safety = s.positive("integrator.safety", in.safety);
  if (in.safety > 1) throw UsageError(s.name() + ": integrator.safety must not exceed 1");
  in.allow_unstable = s.flag("integrator.allow_unstable", in.allow_unstable);
  d.stop.max_steps = s.integer("stop.max_steps", d.stop.max_steps);
  d.stop.steps_without_breaking = s.integer("stop.steps_without_breaking", d.stop.steps_without_breaking);
  if (d.stop.max_steps <= 0) throw UsageError(s.name() + ": stop.max_steps must be positive");
  if (d.stop.steps_without_breaking < 0)
    throw UsageError(s.name() + ": stop.steps_without_breaking must not be negative (0: off)");
  d.output.frame_interval = s.positive("output.frame_interval", d.output.frame_interval);
  d.output.observe_every = s.integer("output.observe_every", d.output.observe_every);
  if (d.output.observe_every <= 0) throw UsageError(s.name() + ": output.observe_every must be positive");
  return d;
}

}  // namespace frac::dem
