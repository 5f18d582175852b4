// mesh-gen: makes the reference meshes of both models and checks mesh files.
//   voronoi     polygon cells of the vectorizable random lattice, with beams (polygon DEM)
//   triangular  mass points on a triangular lattice, with bonds (rubber lattice)
//   check       validates a mesh file and prints a summary
#include <iostream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "mesh/check.hpp"
#include "mesh/random_lattice.hpp"
#include "mesh/triangular_lattice.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

// Writes a mesh with its header, atomically, and says what was written.
template <class Mesh>
void write_mesh_file(const Mesh& m, const ToolRun& run, const cli::CommonOptions& common) {
  io::OutputFile out(common.output);
  io::write_header(out.root(), "mesh", run, out.uuid());
  io::write_mesh(out.root(), m);
  out.commit();
  if (!common.quiet) {
    const auto report = [&] {
      if constexpr (std::is_same_v<Mesh, mesh::CellMesh>)
        return mesh::check_cell_mesh(m);
      else
        return mesh::check_node_mesh(m);
    }();
    std::cerr << "mesh-gen: wrote " << (common.output == "-" ? "standard output" : common.output) << "\n"
              << report.summary;
  }
}

int voronoi(int argc, const char* const* argv, const std::string& command_line) {
  const cli::ToolSpec spec{
      "mesh-gen voronoi", "[options]",
      "Cuts a rectangle or a disc into the Voronoi polygons of a vectorizable random lattice "
      "(one site per grid cell, thrown in a square of side disorder*g around the cell centre) "
      "and joins every pair of cells sharing a side by a beam. Lengths in metres.",
      "  mesh-gen voronoi --shape rect --size 0.40x0.20 --cells 40x20 --disorder 1 --seed 7 -o block.h5\n"
      "  mesh-gen voronoi --shape disc --diameter 0.40 --cells 1100 --seed 7 -o disc.h5"};
  cli::CommonOptions common;
  mesh::RandomLatticeOptions opt;
  std::string size = "0.40x0.20", cells;
  po::options_description desc("Options");
  desc.add_options()("shape", po::value(&opt.shape)->default_value("rect"), "rect or disc")(
      "size", po::value(&size)->default_value(size), "rect: width x height in m, e.g. 0.40x0.20")(
      "diameter", po::value(&opt.diameter)->default_value(0.40), "disc: diameter in m")(
      "cells", po::value(&cells)->required(), "rect: grid cells NXxNY (e.g. 40x20); disc: approximate number of cells")(
      "disorder", po::value(&opt.disorder)->default_value(1.0), "disorder a/g in [0,1]; 0 gives the square grid")(
      "disorder-region", po::value(&opt.disorder_region)->default_value("square"),
      "region the site is thrown in: square (side a) or disc (radius a)")(
      "min-section", po::value(&opt.min_section)->default_value(1e-6),
      "drop beams whose shared side is below this fraction of the spacing");
  cli::add_common(desc, common, cli::kOutput | cli::kSeed | cli::kQuiet | cli::kConfig);
  const auto vm = cli::parse(argc, argv, spec, desc);
  check_file_roles({{"--config", common.config}}, {{"-o", common.output}});

  opt.seed = common.seed;
  mesh::refuse_ignored_options(opt, cli::given_options(vm));
  if (opt.shape == "rect") {
    const auto wh = cli::parse_pair_double(size, "--size");
    const auto n = cli::parse_pair_int(cells, "--cells");
    opt.width = wh[0], opt.height = wh[1], opt.nx = n[0], opt.ny = n[1];
  } else if (opt.shape == "disc") {
    try {
      std::size_t used = 0;
      opt.cells = std::stoll(cells, &used);
      if (used != cells.size()) throw std::invalid_argument(cells);
    } catch (const std::logic_error&) {
      throw UsageError("--cells: a disc takes one number of cells, got '" + cells + "'");
    }
  }
  const auto m = mesh::make_random_lattice(opt);

  ToolRun run = start_run("mesh-gen", command_line);
  run.parameters = cli::resolved_options(vm);
  run.seed = std::to_string(common.seed);
  write_mesh_file(m, run, common);
  return kExitOk;
}

int triangular(int argc, const char* const* argv, const std::string& command_line) {
  const cli::ToolSpec spec{"mesh-gen triangular", "[options]",
                           "Places nx x ny mass points on a triangular lattice of spacing Delta, close-packed rows "
                           "along x or y, joined by nearest-neighbour bonds; an optional notch cuts the bonds across "
                           "the middle line from the left edge. Lengths in metres.",
                           "  mesh-gen triangular --nodes 400x200 --spacing 1e-3 --notch 0.05 -o sheet.h5"};
  cli::CommonOptions common;
  mesh::TriangularLatticeOptions opt;
  std::string nodes;
  po::options_description desc("Options");
  desc.add_options()("nodes", po::value(&nodes)->required(), "nodes along x and y, NXxNY")(
      "spacing", po::value(&opt.spacing)->required(), "lattice spacing Delta in m")(
      "rows-along", po::value(&opt.rows_along)->default_value("x"), "close-packed rows along x or y")(
      "notch", po::value(&opt.notch)->default_value(0.0), "length in m of the cut from the left edge (0: none)");
  cli::add_common(desc, common, cli::kOutput | cli::kQuiet | cli::kConfig);
  const auto vm = cli::parse(argc, argv, spec, desc);
  check_file_roles({{"--config", common.config}}, {{"-o", common.output}});

  const auto n = cli::parse_pair_int(nodes, "--nodes");
  opt.nx = n[0], opt.ny = n[1];
  const auto m = mesh::make_triangular_lattice(opt);

  ToolRun run = start_run("mesh-gen", command_line);
  run.parameters = cli::resolved_options(vm);
  write_mesh_file(m, run, common);
  return kExitOk;
}

int check(int argc, const char* const* argv, const std::string&) {
  const cli::ToolSpec spec{"mesh-gen check", "FILE|-",
                           "Validates a mesh file (convex counter-clockwise cells, areas, unique beams between cells "
                           "that share a side, bond lengths) and prints a summary (none with -q). Exit 2 when an "
                           "invariant fails.",
                           "  mesh-gen check block.h5\n  mesh-gen voronoi --cells 40x20 | mesh-gen check -"};
  cli::CommonOptions common;
  std::string input;
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&input)->required(), "mesh file, or - for standard input");
  cli::add_common(desc, common, cli::kQuiet | cli::kConfig);
  po::positional_options_description positional;
  positional.add("input", 1);
  cli::parse(argc, argv, spec, desc, positional);

  const io::Group root = io::open_input(input);
  io::check_header(root, {"mesh", "run"});
  const auto report = io::mesh_kind(root) == io::MeshKind::cells
                          ? mesh::check_cell_mesh(io::read_cell_mesh_as_stored(root))
                          : mesh::check_node_mesh(io::read_node_mesh_as_stored(root));
  if (!common.quiet) std::cout << input << "\n" << report.summary;
  if (!report.ok()) {
    for (const auto& f : report.failures) std::cerr << "mesh-gen check: " << input << ": " << f << "\n";
    throw InputError(input + ": invalid mesh (" + std::to_string(report.failures.size()) + " failed invariants)");
  }
  if (!common.quiet) std::cout << "ok\n";
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_subcommands("mesh-gen", argc, argv,
                              {{"voronoi", {"polygon cells of the vectorizable random lattice, with beams", voronoi}},
                               {"triangular", {"triangular lattice of mass points, with bonds", triangular}},
                               {"check", {"validate a mesh file and print a summary", check}}});
}
