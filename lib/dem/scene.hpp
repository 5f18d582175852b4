#pragma once
// A DEM scene resolved from its file (data/scenes/*.ini) and the command-line overrides
// (physics/polygon-dem.md §8, DESIGN.md §4): material, physics switches, loading, integrator, stop
// rule and output plan. Defaults are Table 1 of the paper in SI.
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "dem/contact_laws.hpp"
#include "dem/material.hpp"
#include "dynamics/integrator.hpp"

namespace frac::dem {

// The loading's parameters; its kind (`name`) is a row of dem/loading's table, which reads the keys it uses.
struct Loading {
  std::string name = "none";
  // uniaxial and confined-compression: boundary layers move apart (tension) or together (compression)
  // at `boundary_speed` each, reached by constant acceleration over `ramp`.
  bool tension = true;
  double boundary_speed = 0.05;  // m/s
  double ramp = 1e-3;            // s
  double layer_depth = 0;        // m; cells whose centroid lies within it of the edge (0: one spacing g)
  // explosion and pulse: kinetic energy E0 given to the neighbours of the central cell.
  double energy = 500.0;  // J (for the scene's thickness)
  // impact: speed of the projectile cell at the middle of the bottom layer, into the block (+y).
  double impact_speed = 400.0;  // m/s
  // impact: if > 0, the projectile's kinetic energy instead (J): its speed is √(2E/m) for the mass of
  // the cell the mesh puts there (the paper's 400 m/s came with ≈ 457 J, a 5.7 g cell).
  double impact_energy = 0.0;
  // impact: 0 = the projectile is one cell; w > 0 = every cell whose centroid lies in the w × w square on
  // the middle of the bottom edge (m): the same projectile on meshes of any cell size.
  double impact_width = 0.0;
};

struct IntegratorSettings {
  dynamics::IntegratorKind kind = dynamics::IntegratorKind::gear5;
  // gear5's r3..r5 at t = 0: zero (the usual start, O(dt²) globally) or exact (from the equations of
  // motion, dynamics::taylor_derivatives; O(dt⁵) on smooth problems). Verlet ignores it.
  dynamics::StartKind start = dynamics::StartKind::zero;
  double dt = 0;        // s; 0 = auto
  double safety = 0.5;  // auto dt = safety × bound
  bool allow_unstable = false;
};

struct StopRule {
  double t_max = 0.01;  // s
  long long max_steps = 100000000;
  long long steps_without_breaking = 300;  // after the first break; 0 = off
};

struct OutputPlan {
  double frame_interval = 1e-4;     // s between trajectory frames (the final state is always a frame)
  long long observe_every = 10;     // steps between observable samples
  std::vector<std::string> frames;  // the datasets of every frame (dem/frames' rows), position among them
};

struct DemScene {
  Material material;
  Physics physics;
  Loading loading;
  IntegratorSettings integrator;
  StopRule stop;
  OutputPlan output;
};

// UsageError naming the key and its range for a value out of range (speeds, moduli, densities, rates
// beyond core/physical_limits.hpp are refused as absurd). The contact laws a scene can switch on are the rows of
// `laws`.
DemScene read_dem_scene(Scene& scene, const ContactLawTable& laws = contact_law_table());
// The keys a scene for a run must give itself: loading.kind (an empty or stray scene would run on
// defaults alone, doing nothing).
void require_run_keys(const Scene& scene);

}  // namespace frac::dem
