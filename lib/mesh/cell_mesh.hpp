#pragma once
// A solid cut into convex polygons (cells) joined by beams: the reference state of the polygon DEM.
// Struct of arrays; lengths in metres. Written and read by io/mesh_io.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "geometry/vec2.hpp"

namespace frac::mesh {

using geometry::Vec2;

struct CellMesh {
  // Polygons: cell k has vertices vertex[vertex_offset[k] .. vertex_offset[k+1]), counter-clockwise,
  // in the body frame (relative to its centroid). vertex_offset has size cells + 1.
  std::vector<std::int64_t> vertex_offset{0};
  std::vector<Vec2> vertex;
  std::vector<Vec2> centroid;         // m, reference position of each cell's centroid
  std::vector<double> area;           // m^2
  std::vector<double> second_moment;  // m^4, polar second moment of area about the centroid

  // Beams: one per pair of cells sharing a side of positive length, cell_a < cell_b, sorted.
  std::vector<std::array<std::int64_t, 2>> beam;
  std::vector<double> beam_length;   // m, distance between the two centroids (l0)
  std::vector<double> beam_section;  // m, length of the shared side (S)

  // How the mesh was made (recorded as attributes of /particles/cells).
  std::string shape;                       // "rect" or "disc"
  double spacing = 0.0;                    // m, grid cell size g of the vectorizable random lattice
  double disorder = 0.0;                   // a / g in [0, 1]
  std::string disorder_region = "square";  // "square" (offsets in [-a/2, a/2]^2) or "disc" (radius a)
  std::array<double, 4> bounds{};          // m, domain box: xmin, ymin, xmax, ymax

  std::size_t cells() const { return centroid.size(); }
  std::size_t beams() const { return beam.size(); }
  std::span<const Vec2> polygon(std::size_t k) const {
    return {vertex.data() + vertex_offset[k], static_cast<std::size_t>(vertex_offset[k + 1] - vertex_offset[k])};
  }
  // Vertices of cell k in world coordinates (reference state).
  std::vector<Vec2> world_polygon(std::size_t k) const;
};

// A mesh from polygons given in world coordinates (counter-clockwise) and beams given as cell pairs
// with their sections: centroids, areas, second moments and body-frame vertices computed here, beam
// lengths from the centroids. For hand-built scenes (tests, hard cases); spacing g = `spacing`.
CellMesh make_cell_mesh(const std::vector<std::vector<Vec2>>& polygons,
                        const std::vector<std::array<std::int64_t, 2>>& beams, const std::vector<double>& sections,
                        double spacing);

// nx × ny unit squares (cell k = j·nx + i centred at (i + ½, j + ½)), a beam of length 1 and section 1
// between side neighbours: the simplest cell mesh, for hand-built tests.
CellMesh make_square_grid(int nx, int ny);

}  // namespace frac::mesh
