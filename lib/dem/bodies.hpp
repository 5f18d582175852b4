#pragma once
// The cells as rigid bodies: static properties from the mesh and the material, and the layout of the
// flat coordinate vector the integrators advance: q = [x_0..x_{N-1}, y_0..y_{N-1}, φ_0..φ_{N-1}]
// (centroid position in m, accumulated angle in rad, φ = 0 in the reference state).
#include <span>
#include <vector>

#include "dem/material.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

struct Bodies {
  std::size_t n = 0;
  std::vector<double> mass;          // ρ h A, kg
  std::vector<double> inertia;       // ρ h J_c, kg m^2
  std::vector<double> diameter;      // equal-area diameter r = 2 sqrt(A/π), m (the paper's r)
  std::vector<double> bound_radius;  // largest vertex distance from the centroid, m
  double max_bound_radius = 0;
  double length_scale = 0;  // the mesh spacing g, m (contact tolerances)
};

Bodies make_bodies(const mesh::CellMesh& mesh, const Material& material);

// Views of one state (q or v) of N bodies.
struct Coords {
  std::span<const double> x, y, phi;
};
inline Coords coords(std::span<const double> q, std::size_t n) {
  return {q.subspan(0, n), q.subspan(n, n), q.subspan(2 * n, n)};
}
struct MutableCoords {
  std::span<double> x, y, phi;
};
inline MutableCoords coords(std::span<double> q, std::size_t n) {
  return {q.subspan(0, n), q.subspan(n, n), q.subspan(2 * n, n)};
}

}  // namespace frac::dem
