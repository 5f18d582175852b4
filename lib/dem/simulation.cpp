#include "dem/simulation.hpp"

#include <cmath>
#include <new>

#include "core/memory.hpp"

namespace frac::dem {

Simulation::Simulation(const mesh::CellMesh& mesh, const DemScene& s) try
    : cell_mesh(&mesh),
      scene(s),
      model(mesh, s.material, s.physics),
      q0(3 * mesh.cells(), 0.0),
      v0(3 * mesh.cells(), 0.0) {
  const std::size_t n = mesh.cells();
  for (std::size_t k = 0; k < n; ++k) {
    q0[k] = mesh.centroid[k].x();
    q0[n + k] = mesh.centroid[k].y();
  }
  if (!s.physics.beams) model.beams().remove_all();
  setup = apply_loading(s.loading, mesh, model, v0);
  time_step = choose_time_step(mesh, s.material, s.physics, s.integrator.kind, s.integrator.dt, s.integrator.safety,
                               s.integrator.allow_unstable);
  integrator = dynamics::make_integrator(s.integrator.kind);
} catch (const std::bad_alloc&) {
  throw out_of_memory("the DEM model of " + std::to_string(mesh.cells()) + " cells");
}

KickReport kick_report(const Simulation& sim) {
  KickReport r;
  const std::size_t n = sim.model.bodies().n;
  const auto& m = sim.model.bodies().mass;
  double px = 0, py = 0, scale = 0, speed = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double vx = sim.v0[k], vy = sim.v0[n + k];
    const double v = std::hypot(vx, vy);
    if (v == 0) continue;
    ++r.cells;
    px += m[k] * vx;
    py += m[k] * vy;
    scale += m[k] * v;
    speed += v;
    r.kinetic_energy += 0.5 * m[k] * v * v;
  }
  if (r.cells > 0) {
    r.mean_speed = speed / static_cast<double>(r.cells);
    r.momentum_over_scale = std::hypot(px, py) / scale;
  }
  return r;
}

}  // namespace frac::dem
