#pragma once
// What several unit tests share: a fresh folder for a test's files, and small meshes.
#include <filesystem>
#include <string>

#include "core/provenance.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::test {

// <temporary folder>/fracture-test-<name>-<8 random hex digits>, created.
inline std::filesystem::path temp_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("fracture-test-" + name + "-" + make_uuid().substr(0, 8));
  std::filesystem::create_directories(dir);
  return dir;
}

// Two nodes 1 m apart joined by one intact bond (a 2 × 1 lattice).
inline mesh::NodeMesh two_node_mesh() {
  mesh::NodeMesh m;
  m.position = {mesh::Vec2(0, 0), mesh::Vec2(1, 0)};
  m.bond = {{0, 1}};
  m.bond_length = {1.0};
  m.intact = {1};
  m.nx = 2, m.ny = 1, m.spacing = 1.0;
  return m;
}

}  // namespace frac::test
