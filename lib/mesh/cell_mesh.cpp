#include "mesh/cell_mesh.hpp"

namespace frac::mesh {

std::vector<Vec2> CellMesh::world_polygon(std::size_t k) const {
  const auto body = polygon(k);
  std::vector<Vec2> world;
  world.reserve(body.size());
  for (const auto& p : body) world.push_back(p + centroid[k]);
  return world;
}

}  // namespace frac::mesh
