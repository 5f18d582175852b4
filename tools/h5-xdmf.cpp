// h5-xdmf: writes the XDMF sidecar of a mesh or run file, so ParaView and VisIt open it directly.
#include <filesystem>
#include <iostream>
#include <optional>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "io/hdf5.hpp"
#include "io/header.hpp"
#include "io/xdmf.hpp"
#include "render/run_picture.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

// The sidecar's options from --polygons, --polygon-limit and --flavour.
io::XdmfOptions xdmf_options(const std::string& polygons, std::size_t limit, const std::string& flavour) {
  io::XdmfOptions opt;
  if (polygons == "auto")
    opt.polygons = io::XdmfPolygons::automatic;
  else if (polygons == "on")
    opt.polygons = io::XdmfPolygons::on;
  else if (polygons == "off")
    opt.polygons = io::XdmfPolygons::off;
  else
    throw UsageError("--polygons: unknown value '" + polygons + "' (auto, on or off)");
  opt.inline_vertex_limit = limit;
  if (flavour == "xdmf3")
    opt.flavour = io::XdmfFlavour::xdmf3;
  else if (flavour == "xdmf2")
    opt.flavour = io::XdmfFlavour::xdmf2;
  else
    throw UsageError("--flavour: unknown value '" + flavour + "' (xdmf3 or xdmf2)");
  return opt;
}

void print_report(const io::XdmfReport& report, const std::string& output) {
  for (const auto& note : report.notes) std::cerr << "h5-xdmf: note: " << note << "\n";
  std::cerr << "h5-xdmf: wrote " << (output == "-" ? std::string("standard output") : output) << ": " << report.bodies
            << " bodies, " << report.links << " links, "
            << (report.frames ? std::to_string(report.frames) + " frames" : std::string("no frames (mesh)"))
            << (report.polygon_vertices ? ", polygons inline (" + std::to_string(report.polygon_vertices) + " vertices)"
                                        : std::string())
            << "\n";
}

int run(int argc, char** argv) {
  const cli::ToolSpec spec{
      "h5-xdmf", "FILE.h5 [options] [-o FILE.xmf]",
      "Writes an XDMF 3 sidecar for a mesh or run file: the reference polygons (inline), one point per cell or "
      "node with every per-body dataset and time series as attributes, the beams or bonds as two-point "
      "polylines with their strain and intact flags; a run becomes a temporal collection, one grid per "
      "trajectory frame, referring to slabs of the HDF5 datasets in place. Open the .xmf in ParaView "
      "(Xdmf3 Reader S or T), or write --flavour xdmf2 for VisIt and ParaView's legacy XDMF Reader. The sidecar names "
      "the HDF5 file by its path relative to the sidecar: keep them "
      "together. See docs/xdmf.md.",
      "  h5-xdmf explosion.h5                     # writes explosion.xmf\n"
      "  h5-xdmf explosion.h5 --fragments fragments.h5 -o explosion-fragments.xmf\n"
      "  h5-xdmf crack.h5 --flavour xdmf2 -o crack-visit.xmf\n"
      "  paraview explosion.xmf"};
  cli::CommonOptions common;
  std::string input, output, fragments, polygons, flavour;
  std::size_t limit = 500000;  // (negative values refused by cli::parse, as for every unsigned option)
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&input)->required(),
                     "mesh or run file (a named file: the sidecar refers to it)")(
      "output,o", po::value(&output),
      "sidecar to write (default: the input with extension .xmf; - for standard "
      "output)")("fragments", po::value(&fragments), "fragments file of this run: adds the cell attribute 'fragment'")(
      "polygons", po::value(&polygons)->default_value("auto"),
      "write the reference polygons inline: auto (up to "
      "--polygon-limit vertices), on, off")("polygon-limit", po::value(&limit)->default_value(limit),
                                            "vertices up to which --polygons auto writes them")(
      "flavour", po::value(&flavour)->default_value("xdmf3"),
      "how frames are referenced: xdmf3 (ParaView's Xdmf3 "
      "readers) or xdmf2 (HyperSlab DataItems: VisIt, ParaView's legacy XDMF Reader)");
  cli::add_common(desc, common, cli::kQuiet | cli::kConfig);
  po::positional_options_description positional;
  positional.add("input", 1);
  cli::parse(argc, argv, spec, desc, positional);

  if (input == "-")
    throw UsageError(
        "h5-xdmf reads a named file, not standard input: the sidecar refers to the file's datasets by "
        "its name");
  io::XdmfOptions opt = xdmf_options(polygons, limit, flavour);
  if (output.empty()) output = std::filesystem::path(input).replace_extension(".xmf").string();
  check_file_roles({{"FILE", input}, {"--fragments", fragments}, {"--config", common.config}}, {{"-o", output}});

  const io::Group root = io::open_input(input);
  ToolRun run = start_run("h5-xdmf", cli::command_line(argc, argv));
  io::add_input(run, root);
  opt.data_file = io::relative_reference(input, output);
  std::optional<io::Group> fragments_root;
  if (!fragments.empty()) {
    if (fragments == "-") throw UsageError("--fragments: a named file, not standard input");
    fragments_root.emplace(io::open_input(fragments));
    io::add_input(run, *fragments_root);
    opt.fragments = &*fragments_root;
    opt.fragments_file = io::relative_reference(fragments, output);
    if (!render::counted_from(*fragments_root, root) && !common.quiet)
      std::cerr << "h5-xdmf: warning: " << fragments << " was not counted from " << input
                << " (its provenance does not name that file)\n";
  }
  opt.provenance = provenance_line(run);
  io::XdmfReport report;
  const std::string text = io::xdmf_document(root, opt, &report);
  io::write_text_file(output, text);
  if (!common.quiet) print_report(report, output);
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("h5-xdmf", [&] { return run(argc, argv); });
}
