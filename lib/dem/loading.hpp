#pragma once
// Loading protocols (physics/polygon-dem.md §8): prescribed boundary layers for the uniaxial and the
// confined compression tests, and the initial kicks of the explosion, the pulse and the impact.
// `apply_loading` sets up the model's prescribed coordinates and the initial velocities; the
// returned LoadingProbe measures the test's stress and strains from a state.
#include <span>
#include <string>
#include <vector>

#include "dem/model.hpp"
#include "dem/scene.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

struct LoadingProbe {
  bool active = false;  // uniaxial or confined compression
  std::vector<std::size_t> top, bottom, left, right;  // cells of the boundary layers and side columns
  double width0 = 0, length0 = 0;  // m, initial W (mean x right − left) and L (mean y top − bottom)
  double thickness = 0;
  // σ = (F_bottom − F_top)/(2 W h): the y force the sample exerts on the layers; tension positive. Pa.
  double stress(std::span<const double> force, std::size_t n) const;
  double axial_strain(std::span<const double> q, std::size_t n) const;    // ΔL/L
  double lateral_strain(std::span<const double> q, std::size_t n) const;  // ΔW/W
};

struct LoadingSetup {
  LoadingProbe probe;
  std::vector<std::size_t> kicked;  // cells given an initial velocity
  std::size_t source = 0;           // explosive or projectile cell
  double kinetic_energy = 0;        // J, given at t = 0
};

// Applies the scene's loading to `model` and writes the initial velocities into v0 (size 3N).
// InputError when the mesh cannot carry the loading (e.g. an explosive cell on the boundary).
LoadingSetup apply_loading(const Loading& loading, const mesh::CellMesh& mesh, Model& model, std::span<double> v0);

}  // namespace frac::dem
