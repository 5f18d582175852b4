#include "mesh/cell_mesh.hpp"

#include <algorithm>

#include "geometry/polygon.hpp"

namespace frac::mesh {

std::vector<Vec2> CellMesh::world_polygon(std::size_t k) const {
  const auto body = polygon(k);
  std::vector<Vec2> world;
  world.reserve(body.size());
  for (const auto& p : body) world.push_back(p + centroid[k]);
  return world;
}

CellMesh make_cell_mesh(const std::vector<std::vector<Vec2>>& polygons,
                        const std::vector<std::array<std::int64_t, 2>>& beams, const std::vector<double>& sections,
                        double spacing) {
  CellMesh m;
  m.shape = "custom";
  m.spacing = spacing;
  m.bounds = {1e300, 1e300, -1e300, -1e300};
  for (const auto& poly : polygons) {
    const Vec2 c = geometry::centroid(poly);
    m.centroid.push_back(c);
    m.area.push_back(geometry::signed_area(poly));
    m.second_moment.push_back(geometry::polar_second_moment(poly));
    for (const Vec2& v : poly) {
      m.vertex.push_back(v - c);
      m.bounds = {std::min(m.bounds[0], v.x()), std::min(m.bounds[1], v.y()), std::max(m.bounds[2], v.x()),
                  std::max(m.bounds[3], v.y())};
    }
    m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
  }
  m.beam = beams;
  m.beam_section = sections;
  for (const auto& b : beams)
    m.beam_length.push_back(
        (m.centroid[static_cast<std::size_t>(b[1])] - m.centroid[static_cast<std::size_t>(b[0])]).norm());
  return m;
}

CellMesh make_square_grid(int nx, int ny) {
  CellMesh m;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      for (auto v : {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)}) m.vertex.push_back(v);
      m.vertex_offset.push_back(m.vertex_offset.back() + 4);
      m.centroid.emplace_back(i + 0.5, j + 0.5);
      m.area.push_back(1.0);
      m.second_moment.push_back(1.0 / 6.0);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int64_t k = j * nx + i;
      if (i + 1 < nx) m.beam.push_back({k, k + 1});
      if (j + 1 < ny) m.beam.push_back({k, k + nx});
    }
  std::sort(m.beam.begin(), m.beam.end());
  m.beam_length.assign(m.beam.size(), 1.0);
  m.beam_section.assign(m.beam.size(), 1.0);
  m.shape = "rect";
  m.spacing = 1.0;
  m.bounds = {0, 0, static_cast<double>(nx), static_cast<double>(ny)};
  return m;
}

}  // namespace frac::mesh
