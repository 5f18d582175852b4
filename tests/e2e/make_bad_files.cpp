// Writes HDF5 files that the tools must refuse: a file of ours holding no mesh, and a mesh file of
// an unknown format version. Used by the end-to-end bad-input tests.
#include <iostream>
#include <string>

#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
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
  return 0;
}
