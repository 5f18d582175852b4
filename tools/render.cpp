// render: draws a mesh or a run frame (or every frame, for a movie) to PNG or SVG with Cairo.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_roles.hpp"
#include "core/provenance.hpp"
#include "io/hdf5.hpp"
#include "io/header.hpp"
#include "render/canvas.hpp"
#include "render/picture_files.hpp"
#include "render/run_picture.hpp"

namespace po = boost::program_options;
using namespace frac;

namespace {

// "a,b,c" -> numbers; UsageError naming the option unless there are `count` finite ones.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option,
                                  const char* form) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string part;
  bool ok = true;
  while (ok && std::getline(in, part, ',')) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(part, &used));
      ok = used == part.size() && std::isfinite(out.back());
    } catch (const std::logic_error&) {
      ok = false;
    }
  }
  if (!ok || out.size() != count) throw UsageError(option + ": expected " + form + ", got '" + text + "'");
  return out;
}
// Every option's value, as parsed.
struct Options {
  cli::CommonOptions common;
  std::string input, colour, fragments, beams, range, view, format;
  long long frame = 0;
  double time = 0;
  bool all_frames = false, axes = false, no_title = false;
  long long every = 1;
  render::CanvasSize size;
  po::variables_map vm;
};

cli::ToolSpec tool_spec() {
  return {"render", "RUN.h5|MESH.h5|- [options] -o PICTURE.png|.svg",
          "Draws a mesh or one frame of a run (or every frame, for a movie) to PNG or SVG. Polygon cells are drawn "
          "turned and moved as in the frame; rubber nodes as dots. Cells or nodes are coloured by fragment (with "
          "--fragments), speed, strain (mean strain of their beams or bonds) or any per-body dataset or time series "
          "of the file; beams and bonds by strain relative to the breaking threshold (material.t_eps of dem-run; the "
          "bond cut-off of rubber-run), broken ones marked with a cross. Colour bars carry their units.",
          "  render explosion.h5 --time 1e-3 -o explosion-1ms.png\n"
          "  render explosion.h5 --fragments fragments.h5 --beams off -o fragments.svg\n"
          "  render explosion.h5 --all-frames --colour speed --beams broken -o movie/explosion-%04d.png\n"
          "  render crack.h5 --frame -1 --axes -o crack.png\n"
          "  render disc.h5 -o mesh.svg"};
}

void parse_options(int argc, char** argv, Options& o) {
  po::options_description desc("Options");
  desc.add_options()("input", po::value(&o.input)->required(), "mesh or run file, or - for standard input")(
      "frame", po::value(&o.frame),
      "frame to draw: 0 the first, -1 the final state (default: the fragments' "
      "frame with --fragments, else -1)")("time", po::value(&o.time), "draw the frame nearest to this time, in s")(
      "all-frames", po::bool_switch(&o.all_frames),
      "draw every frame; -o needs a frame-number pattern, e.g. "
      "picture-%04d.png (numbered 0, 1, 2, ... for a movie)")("every", po::value(&o.every)->default_value(1),
                                                              "with --all-frames: every N-th frame only")(
      "colour", po::value(&o.colour),
      "what colours cells or nodes: fragment, speed, strain, none, or a dataset or "
      "time series with one value per body (e.g. angle, angular_velocity, /particles/cells/area); default: "
      "fragment with --fragments, else speed (DEM run), strain (rubber run), none (mesh)")(
      "fragments", po::value(&o.fragments), "fragments file of this run (fragment-count) for --colour fragment")(
      "beams", po::value(&o.beams)->default_value("strain"),
      "beams or bonds: strain (coloured by strain relative to "
      "the breaking threshold, broken ones crossed), broken (only the broken ones), off")(
      "range", po::value(&o.range), "colour range of the cells' or nodes' field, MIN,MAX (default: the data's)")(
      "view", po::value(&o.view), "region shown, XMIN,YMIN,XMAX,YMAX in m (default: everything)")(
      "width", po::value(&o.size.width)->default_value(1000), "picture width in pixels")(
      "height", po::value(&o.size.height)->default_value(0), "picture height in pixels (0: from the view's aspect)")(
      "axes", po::bool_switch(&o.axes), "draw axes with ticks in metres")(
      "no-title", po::bool_switch(&o.no_title), "leave out the title line (file, frame, time)")(
      "format", po::value(&o.format), "png or svg (default: from the output's extension; png for standard output)");
  cli::add_common(desc, o.common, cli::kOutput | cli::kQuiet | cli::kConfig,
                  "picture file, .png or .svg (with --all-frames a frame-number pattern); '-' writes the PNG (or "
                  "--format svg) to standard output");
  po::positional_options_description positional;
  positional.add("input", 1);
  o.vm = cli::parse(argc, argv, tool_spec(), desc, positional);
}

// Checks the frame choice, the picture's size and the output; returns the picture format.
render::ImageFormat check_output(const Options& o, int choices) {
  const po::variables_map& vm = o.vm;
  const render::CanvasSize& size = o.size;
  if (choices > 1) throw UsageError("--frame, --time and --all-frames: give one of them");
  if (o.every < 1) throw UsageError("--every: must be at least 1, got " + std::to_string(o.every));
  if (size.width < 100 || size.width > 20000)
    throw UsageError("--width: between 100 and 20000 pixels, got " + std::to_string(size.width));
  if (size.height != 0 && (size.height < 100 || size.height > 20000))
    throw UsageError("--height: 0 (automatic) or between 100 and 20000 pixels, got " + std::to_string(size.height));
  if (vm.count("time") && !std::isfinite(o.time)) throw UsageError("--time: not a finite number");
  const std::string& output = o.common.output;
  const render::ImageFormat fmt = vm.count("format") ? render::format_from_text(o.format)
                                  : output == "-"    ? render::ImageFormat::png
                                                     : render::format_from_name(output);
  // (a name without an extension, such as /dev/null, takes --format's)
  if (vm.count("format") && std::filesystem::path(output).has_extension() && render::format_from_name(output) != fmt)
    throw UsageError("--format " + o.format + " does not match the extension of '" + output + "'");
  if (o.all_frames && output == "-")
    throw UsageError("--all-frames: write to files (-o picture-%04d.png), not to standard output");
  if (o.all_frames) render::numbered_name(output, 0);  // checks the pattern before any work
  return fmt;
}

render::PictureOptions picture_options(const Options& o) {
  render::PictureOptions opt;
  opt.colour = o.colour;
  opt.links = o.beams;
  render::link_mode_from_text(o.beams);
  opt.axes = o.axes;
  opt.title = !o.no_title;
  opt.name = o.input == "-" ? "standard input" : "";
  if (o.vm.count("range")) {
    const auto r = parse_numbers(o.range, 2, "--range", "MIN,MAX");
    if (!(r[1] > r[0])) throw UsageError("--range: MAX must be above MIN, got '" + o.range + "'");
    opt.range = std::array<double, 2>{r[0], r[1]};
  }
  if (o.vm.count("view")) {
    const auto v = parse_numbers(o.view, 4, "--view", "XMIN,YMIN,XMAX,YMAX");
    if (!(v[2] > v[0] && v[3] > v[1]))
      throw UsageError("--view: XMAX must exceed XMIN and YMAX YMIN, got '" + o.view + "'");
    opt.view = std::array<double, 4>{v[0], v[1], v[2], v[3]};
  }
  return opt;
}

// The fragments file's labels (--fragments), recorded as an input; a warning when it was not counted from
// this run.
std::optional<render::FragmentLabels> read_labels(const Options& o, const io::Group& root, ToolRun& run,
                                                  std::optional<io::Group>& fragments_root) {
  if (!o.vm.count("fragments")) return std::nullopt;
  fragments_root.emplace(io::open_input(o.fragments));
  io::add_input(run, *fragments_root);
  std::optional<render::FragmentLabels> labels = render::read_fragment_labels(*fragments_root);
  if (!render::counted_from(*fragments_root, root) && !o.common.quiet)
    std::cerr << "render: warning: " << o.fragments << " was not counted from " << o.input
              << " (its provenance does not name that file)\n";
  return labels;
}

int run(int argc, char** argv) {
  Options o;
  parse_options(argc, argv, o);
  const po::variables_map& vm = o.vm;
  const std::string& output = o.common.output;
  const std::vector<FileRole> inputs{{"RUN", o.input}, {"--fragments", o.fragments}, {"--config", o.common.config}};
  if (!o.all_frames) check_file_roles(inputs, {{"-o", output}});
  const int choices = static_cast<int>(vm.count("frame")) + static_cast<int>(vm.count("time")) + (o.all_frames ? 1 : 0);
  const render::ImageFormat fmt = check_output(o, choices);
  const render::PictureOptions opt = picture_options(o);

  const io::Group root = io::open_input(o.input);
  ToolRun run = start_run("render", cli::command_line(argc, argv));
  io::add_input(run, root);
  std::optional<io::Group> fragments_root;
  const std::optional<render::FragmentLabels> labels = read_labels(o, root, run, fragments_root);
  const std::string provenance = provenance_line(run);
  render::RunPicture picture(root, labels, opt);
  if (!picture.is_run() && choices > 0)
    throw UsageError(std::string(vm.count("frame")  ? "--frame"
                                 : vm.count("time") ? "--time"
                                                    : "--all-frames") +
                     ": " + o.input + " is a mesh file: it has no frames");

  auto say = [&](const std::string& text) {
    if (!o.common.quiet) std::cerr << "render: " << text << "\n";
  };
  if (!o.all_frames) {
    const long long k = vm.count("frame")  ? picture.frame_index(o.frame)
                        : vm.count("time") ? picture.frame_at_time(o.time)
                                           : picture.default_frame();
    if (labels && picture.colour() == "fragment" && picture.is_run() && k != labels->frame)
      say("warning: the fragments were counted at frame " + std::to_string(labels->frame) + ", drawing frame " +
          std::to_string(k));
    const auto px = render::write_frame_picture(picture, k, o.size, fmt, output, provenance);
    say("wrote " + (output == "-" ? std::string("standard output") : output) + " (" + std::to_string(px[0]) + "x" +
        std::to_string(px[1]) + (picture.is_run() ? ", frame " + std::to_string(k) : "") + ")");
    return kExitOk;
  }

  std::vector<long long> frames;
  for (long long k = 0; k < static_cast<long long>(picture.frames()); k += o.every) frames.push_back(k);
  picture.fix_across(frames);  // one view and one colour range for the whole sequence
  render::write_picture_sequence(picture, frames, o.size, fmt, output, provenance, inputs);
  say("wrote " + std::to_string(frames.size()) + " pictures, " + render::numbered_name(output, 0) + " to " +
      render::numbered_name(output, static_cast<long long>(frames.size()) - 1));
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("render", [&] { return run(argc, argv); });
}
