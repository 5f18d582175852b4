#include "dem/material.hpp"

#include <algorithm>
#include <numbers>

#include "core/error.hpp"
#include "core/physical_limits.hpp"

namespace frac::dem {

Material read_material(Scene& s) {
  using limits::kDensity, limits::kModulus, limits::kRate, limits::kThickness;
  Material m;
  m.density = s.in("material.density", m.density, Interval::open_closed(0, kDensity));
  m.thickness = s.in("material.thickness", m.thickness, Interval::open_closed(0, kThickness));
  m.grain_modulus = s.in("material.grain_modulus", m.grain_modulus, Interval::open_closed(0, kModulus));
  m.beam_modulus = s.in("material.beam_modulus", m.beam_modulus, Interval::open_closed(0, kModulus));
  m.shear_ratio = s.in("material.shear_ratio", m.shear_ratio, Interval::open_closed(0, 1e3));
  m.t_eps = s.positive("material.t_eps", m.t_eps);  // (thresholds may be out of reach: 1e300 is never-break)
  m.t_theta = s.positive("material.t_theta_deg", 4.0) * std::numbers::pi / 180.0;
  m.friction = s.in("material.friction", m.friction, Interval::closed(0, 1e3));
  m.gamma_n = s.in("material.gamma_n", m.gamma_n, Interval::closed(0, kRate));
  m.gamma_t = s.in("material.gamma_t", m.gamma_t, Interval::closed(0, kRate));
  return m;
}

void read_physics_switches(Scene& s, Physics& p) {
  p.contacts = s.flag("physics.contacts", p.contacts);
  p.beams = s.flag("physics.beams", p.beams);
  p.breaking = s.flag("physics.breaking", p.breaking);
  if (p.breaking && !p.beams) throw UsageError(s.name() + ": physics.breaking = on needs physics.beams = on");
}

bool Physics::has(std::string_view law) const { return std::find(laws.begin(), laws.end(), law) != laws.end(); }

}  // namespace frac::dem
