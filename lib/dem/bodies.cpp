#include "dem/bodies.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/polygon.hpp"

namespace frac::dem {

Bodies make_bodies(const mesh::CellMesh& mesh, const Material& material) {
  Bodies b;
  b.n = mesh.cells();
  b.mass.resize(b.n);
  b.inertia.resize(b.n);
  b.diameter.resize(b.n);
  b.bound_radius.resize(b.n);
  const double rho_h = material.density * material.thickness;
  for (std::size_t k = 0; k < b.n; ++k) {
    b.mass[k] = rho_h * mesh.area[k];
    b.inertia[k] = rho_h * mesh.second_moment[k];
    b.diameter[k] = geometry::equal_area_diameter(mesh.area[k]);
    double r = 0;
    for (const auto& v : mesh.polygon(k)) r = std::max(r, v.norm());
    b.bound_radius[k] = r;
    b.max_bound_radius = std::max(b.max_bound_radius, r);
  }
  b.length_scale = mesh.spacing > 0 ? mesh.spacing : 2 * b.max_bound_radius;
  return b;
}

}  // namespace frac::dem
