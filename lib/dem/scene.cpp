#include "dem/scene.hpp"

#include "core/error.hpp"
#include "core/physical_limits.hpp"
#include "dem/frames.hpp"
#include "dem/loading.hpp"

namespace frac::dem {

void require_run_keys(const Scene& s) {
  std::string kinds;
  for (const LoadingRow& row : loading_table()) kinds += (kinds.empty() ? "" : ", ") + row.name;
  s.require("loading.kind", "what the run does: " + kinds);
}

DemScene read_dem_scene(Scene& s, const ContactLawTable& laws) {
  DemScene d;
  d.material = read_material(s);
  read_physics_switches(s, d.physics);
  d.physics.laws = read_contact_laws(s, laws, d.physics.contacts);
  std::vector<std::string> kinds;
  for (const LoadingRow& row : loading_table()) kinds.push_back(row.name);
  d.loading.name = s.choice("loading.kind", "none", kinds);
  loading_row(d.loading.name).read(s, d.loading);
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
  d.output.frames = s.subset("output.frames", frame_names());
  if (d.output.frames.empty() || d.output.frames.front() != "position")
    s.refuse("output.frames", "must name position: the readers of a run find its frames by it");
  return d;
}

}  // namespace frac::dem
