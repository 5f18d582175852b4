#pragma once
// Material and physics switches of a DEM scene (physics/polygon-dem.md §0, §7): Table 1 of Kun et al.
// in SI as defaults, the 2D thickness h that turns areas into masses and moduli into stiffnesses.
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.hpp"

namespace frac::dem {

struct Material {
  double density = 5000.0;              // ρ, kg m^-3
  double thickness = 0.01;              // h, m
  double grain_modulus = 1e9;           // Y, Pa (overlap repulsion)
  double beam_modulus = 5e8;            // E, Pa
  double shear_ratio = 2.0;             // b/a = E/G (the paper: b = 2a, G = E/2)
  double t_eps = 0.03;                  // stretching threshold t_ε
  double t_theta = 0.0698131700797732;  // bending threshold t_Θ, rad (scene key in degrees)
  double friction = 0.0;                // Coulomb coefficient μ
  double gamma_n = 0.0;                 // normal damping rate γ_N, s^-1
  double gamma_t = 0.0;                 // tangential (viscous friction) rate γ_T, s^-1
};

// The physics a scene names; a term that is off is not in the engine's term list.
struct Physics {
  bool contacts = true;
  bool beams = true;
  bool breaking = true;
  // The contact laws on, by the names of their rows in the model's table (dem/contact_laws), in its order:
  // "contact" with the contacts, then those a scene switches on (damping, friction ...).
  std::vector<std::string> laws{"contact"};
  std::vector<std::string> contact_laws() const { return contacts ? laws : std::vector<std::string>{}; }
  bool has(std::string_view law) const;
};

// The [material] section. UsageError naming the key for bad values.
Material read_material(Scene& scene);
// The [physics] switches of the beams, the breaking and the contacts (the contact laws: dem/contact_laws).
void read_physics_switches(Scene& scene, Physics& physics);

}  // namespace frac::dem
