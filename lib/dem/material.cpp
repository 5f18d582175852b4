#include "dem/material.hpp"

#include <numbers>

#include "core/error.hpp"

namespace frac::dem {

Material read_material(Scene& s) {
  Material m;
  m.density = s.positive("material.density", m.density);
  m.thickness = s.positive("material.thickness", m.thickness);
  m.grain_modulus = s.non_negative("material.grain_modulus", m.grain_modulus);
  m.beam_modulus = s.non_negative("material.beam_modulus", m.beam_modulus);
  m.shear_ratio = s.positive("material.shear_ratio", m.shear_ratio);
  m.t_eps = s.positive("material.t_eps", m.t_eps);
  m.t_theta = s.positive("material.t_theta_deg", 4.0) * std::numbers::pi / 180.0;
  m.friction = s.non_negative("material.friction", m.friction);
  m.gamma_n = s.non_negative("material.gamma_n", m.gamma_n);
  m.gamma_t = s.non_negative("material.gamma_t", m.gamma_t);
  return m;
}

Physics read_physics(Scene& s) {
  Physics p;
  p.contacts = s.flag("physics.contacts", p.contacts);
  p.beams = s.flag("physics.beams", p.beams);
  p.breaking = s.flag("physics.breaking", p.breaking);
  p.friction = s.flag("physics.friction", p.friction);
  p.damping = s.flag("physics.damping", p.damping);
  if (p.breaking && !p.beams) throw UsageError(s.name() + ": physics.breaking = on needs physics.beams = on");
  if ((p.friction || p.damping) && !p.contacts)
    throw UsageError(s.name() + ": physics.friction and physics.damping act on contacts: they need physics.contacts = on");
  return p;
}

}  // namespace frac::dem
