// Writes HDF5 files that the tools must refuse: a file of ours holding no mesh, a mesh file of an
// unknown format version, meshes that break one invariant of mesh-gen check each (bad-*.h5, cell
// meshes of an 8x4 block; bad-node-*.h5, node meshes), and run files whose mesh breaks one or whose
// frames hold what no run writes (bad-run-*.h5). Used by the end-to-end bad-input tests.
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"
#include "mesh/random_lattice.hpp"
#include "mesh/triangular_lattice.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_bad_files FOLDER\n";
    return 2;
  }
  const std::string dir = argv[1];
  const frac::ToolRun run = frac::start_run("make_bad_files", "make_bad_files " + dir);
  {
    frac::io::OutputFile out(dir + "/nomesh.h5");
    frac::io::write_header(out.root(), "mesh", run, out.uuid());
    out.commit();
  }
  {
    frac::io::OutputFile out(dir + "/version2.h5");
    frac::io::write_header(out.root(), "mesh", run, out.uuid());
    frac::io::write_mesh(out.root(), frac::mesh::make_triangular_lattice({3, 3, 1e-3, "x", 0.0}));
    out.root().set_attr("format_version", std::vector<std::int64_t>{2, 0});
    out.commit();
  }
  using frac::mesh::CellMesh;
  using frac::mesh::NodeMesh;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  frac::mesh::RandomLatticeOptions block;
  block.width = 0.08, block.height = 0.04, block.nx = 8, block.ny = 4, block.seed = 5;
  const CellMesh good = frac::mesh::make_random_lattice(block);
  const auto cells = [&](const std::string& name, const std::function<void(CellMesh&)>& spoil,
                         const std::function<void(frac::io::Group&)>& after = {}) {
    CellMesh m = good;
    spoil(m);
    frac::io::OutputFile out(dir + "/bad-" + name + ".h5");
    frac::io::write_header(out.root(), "mesh", run, out.uuid());
    frac::io::write_mesh(out.root(), m);
    if (after) after(out.root());
    out.commit();
  };
  cells("nan-vertex", [&](CellMesh& m) { m.vertex[5].x() = nan; });
  cells("nan-centroid", [&](CellMesh& m) { m.centroid[3].y() = nan; });
  cells("clockwise", [](CellMesh& m) {  // cell 2's vertices in reverse order
    std::reverse(m.vertex.begin() + m.vertex_offset[2], m.vertex.begin() + m.vertex_offset[3]);
  });
  cells("non-convex", [](CellMesh& m) {  // cell 2's first vertex pulled in past its centroid
    m.vertex[static_cast<std::size_t>(m.vertex_offset[2])] *= -0.2;
  });
  cells("zero-beam", [](CellMesh& m) { m.beam_length[4] = 0.0; });
  cells("nan-beam", [&](CellMesh& m) { m.beam_length[4] = nan; });
  cells("self-beam", [](CellMesh& m) { m.beam[4][1] = m.beam[4][0]; });
  cells("negative-area", [](CellMesh& m) { m.area[6] = -m.area[6]; });
  cells("nan-area", [&](CellMesh& m) { m.area[5] = nan; });
  cells("inf-spacing", [](CellMesh& m) { m.spacing = std::numeric_limits<double>::infinity(); });
  cells("huge-spacing", [](CellMesh& m) { m.spacing = 1e6; });    // would make every tolerance 1e-2 m
  cells("outside-box", [](CellMesh& m) { m.bounds[2] = 0.04; });  // the right half's centroids outside
  cells("offset-overflow", [](CellMesh& m) { m.vertex_offset[3] = std::numeric_limits<std::int64_t>::max(); });
  cells(
      "short-centroid", [](CellMesh&) {},
      [](frac::io::Group& root) {
        const auto c = root.read<double>("particles/cells/centroid");
        H5Ldelete(root.id(), "particles/cells/centroid", H5P_DEFAULT);
        root.write("particles/cells/centroid", std::span<const double>(c.data(), c.size() - 2), {c.size() / 2 - 1, 2},
                   "m");
      });
  cells(
      "float-offsets", [](CellMesh&) {},
      [](frac::io::Group& root) {
        const auto o = root.read<double>("particles/cells/vertex_offset");
        H5Ldelete(root.id(), "particles/cells/vertex_offset", H5P_DEFAULT);
        root.write("particles/cells/vertex_offset", std::span<const double>(o), {o.size()});
      });
  const auto nodes = [&](const std::string& name, const std::function<void(NodeMesh&)>& spoil) {
    NodeMesh m = frac::mesh::make_triangular_lattice({10, 6, 1e-3, "x", 0.0});
    spoil(m);
    frac::io::OutputFile out(dir + "/bad-node-" + name + ".h5");
    frac::io::write_header(out.root(), "mesh", run, out.uuid());
    frac::io::write_mesh(out.root(), m);
    out.commit();
  };
  nodes("nan", [&](NodeMesh& m) { m.position[7].x() = nan; });
  nodes("bond-length", [](NodeMesh& m) { m.bond_length[3] *= 2; });
  nodes("duplicate-bond", [](NodeMesh& m) { m.bond[4] = m.bond[3]; });
  nodes("nan-spacing", [&](NodeMesh& m) { m.spacing = nan; });
  nodes("overflow", [](NodeMesh& m) { m.nx = std::int64_t{1} << 62, m.ny = 4; });  // nx * ny wraps to 0

  // A copy of cell 5 stacked on it as a 33rd cell, without beams: every other invariant holds.
  cells("stacked-cell", [](CellMesh& m) {
    const auto poly = m.polygon(5);
    m.vertex.insert(m.vertex.end(), poly.begin(), poly.end());
    m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
    m.centroid.push_back(m.centroid[5]), m.area.push_back(m.area[5]), m.second_moment.push_back(m.second_moment[5]);
  });

  // DEM run files of 3 frames at rest (step k, t = 1e-6 k s), each spoiled in one way by `spoil` (the mesh at
  // k = -1, then frame k): every reader of runs must refuse them.
  using Spoil = std::function<void(CellMesh&, int, frac::io::BodyFrame&)>;
  const auto dem_run = [&](const std::string& name, const Spoil& spoil) {
    CellMesh m = good;
    frac::io::BodyFrame f;
    spoil(m, -1, f);
    const std::size_t n = m.cells(), b = m.beams();
    const std::vector<double> mass(n, 1e-3), inertia(n, 1e-8);
    frac::io::OutputFile out(dir + "/bad-run-" + name + ".h5");
    frac::io::write_header(out.root(), "run", frac::start_run("dem-run", "dem-run"), out.uuid());
    frac::io::RunWriter writer(out.root(), m, mass, inertia);
    for (int k = 0; k < 3; ++k) {
      f.position.clear();
      for (const auto& c : m.centroid) f.position.insert(f.position.end(), {c.x(), c.y()});
      f.velocity.assign(2 * n, 0.0), f.angle.assign(n, 0.0), f.angular_velocity.assign(n, 0.0);
      f.intact.assign(b, 1), f.strain.assign(b, 0.0);
      f.step = k, f.time = 1e-6 * k;
      spoil(m, k, f);
      writer.write_frame(f);
    }
    writer.finish();
    out.commit();
  };
  // A mesh with one NaN: every reader of runs refuses the run.
  dem_run("nan-area", [&](CellMesh& m, int k, frac::io::BodyFrame&) {
    if (k < 0) m.area[5] = nan;
  });
  // Frame states no run writes: an intact flag of 7, a negative time, a cell at a NaN position or angle.
  dem_run("intact-7", [](CellMesh&, int k, frac::io::BodyFrame& f) {
    if (k == 2) f.intact[3] = 7;
  });
  dem_run("negative-time", [](CellMesh&, int k, frac::io::BodyFrame& f) {
    if (k == 1) f.time = -1;
  });
  dem_run("nan-position", [&](CellMesh&, int k, frac::io::BodyFrame& f) {
    if (k == 2) f.position[2 * 4] = nan;
  });
  dem_run("nan-angle", [&](CellMesh&, int k, frac::io::BodyFrame& f) {
    if (k == 2) f.angle[6] = nan;
  });
  {
    NodeMesh m = frac::mesh::make_triangular_lattice({10, 6, 1e-3, "x", 0.0});
    m.position[7].y() = nan;
    const std::size_t n = m.nodes(), b = m.bonds();
    frac::ToolRun rubber = frac::start_run("rubber-run", "rubber-run");
    rubber.parameters = {{"loading.stretch_x", "1"},
                         {"loading.stretch_y", "1"},
                         {"boundary.clamp_rows", "0"},
                         {"material.a", "1600"},
                         {"material.b", "1.5"}};
    frac::io::OutputFile out(dir + "/bad-run-node-nan.h5");
    frac::io::write_header(out.root(), "run", rubber, out.uuid());
    frac::io::RunWriter writer(out.root(), m, std::vector<double>(n, 1e-6));
    frac::io::BodyFrame f;
    for (const auto& p : m.position) f.position.insert(f.position.end(), {p.x(), p.y()});
    f.velocity.assign(2 * n, 0.0), f.intact.assign(b, 1), f.strain.assign(b, 0.0);
    for (int k = 0; k < 3; ++k) {
      f.step = k, f.time = 1e-6 * k;
      writer.write_frame(f);
    }
    writer.finish();
    out.commit();
  }
  return 0;
}
