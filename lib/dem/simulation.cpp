#include "dem/simulation.hpp"

namespace frac::dem {

Simulation::Simulation(const mesh::CellMesh& mesh, const DemScene& s)
    : scene(s), model(mesh, s.material, s.physics), q0(3 * mesh.cells(), 0.0), v0(3 * mesh.cells(), 0.0) {
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
}

}  // namespace frac::dem
