#pragma once
// Loading protocols (physics/polygon-dem.md §8) as rows of a table, one a kind (loading.kind): prescribed
// boundary layers for the uniaxial and the confined compression tests, and the initial kicks of the explosion,
// the pulse and the impact. A row reads its keys from the scene and applies itself: the model's prescribed
// coordinates and the initial velocities; the returned LoadingProbe measures the test's stress and strains from
// a state. A new kind is one row.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dem/model.hpp"
#include "dem/scene.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

struct LoadingProbe {
  bool active = false;                                // uniaxial or confined compression
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

struct LoadingRow {
  std::string name;  // loading.kind
  // Its [loading] keys into `loading`.
  std::function<void(Scene& scene, Loading& loading)> read;
  // What it does to the model and the initial velocities v0, `depth` the boundary layers' (m).
  std::function<LoadingSetup(const Loading& loading, const mesh::CellMesh& mesh, Model& model, std::span<double> v0,
                             double depth)>
      apply;
  // The key and value that set the speed of a kick ("loading.energy = 500 J"), for the message that refuses one
  // no solid survives.
  std::function<std::string(const Loading& loading)> kick_source;
};
const std::vector<LoadingRow>& loading_table();
const LoadingRow& loading_row(const std::string& name);  // (std::out_of_range for a name the table lacks)

// Applies the scene's loading to `model` and writes the initial velocities into v0 (size 3N).
// InputError when the mesh cannot carry the loading (e.g. an explosive cell on the boundary).
LoadingSetup apply_loading(const Loading& loading, const mesh::CellMesh& mesh, Model& model, std::span<double> v0);

}  // namespace frac::dem
