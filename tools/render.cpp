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
#include "io/header.hpp"
#include "io/hdf5.hpp"
#include "render/canvas.hpp"
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

// picture-%04d.png with number 7 -> picture-0007.png. The pattern must hold one %d (with an optional
// zero-padded width) and no other % but %%.
std::string numbered(const std::string& pattern, long long number) {
  std::string out;
  int fields = 0;
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    if (pattern[k] != '%') {
      out += pattern[k];
      continue;
    }
    if (k + 1 < pattern.size() && pattern[k + 1] == '%') {
      out += '%';
      ++k;
      continue;
    }
    std::size_t j = k + 1;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
    if (j >= pattern.size() || pattern[j] != 'd' || j - k > 4)
      throw UsageError("--output: '" + pattern + "': the only pattern allowed is a frame number such as %04d");
    const int width = j > k + 1 ? std::stoi(pattern.substr(k + 1, j - k - 1)) : 0;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*lld", width, number);
    out += buf;
    ++fields;
    k = j;
  }
  if (fields != 1)
    throw UsageError("--output: '" + pattern + "': a frame sequence needs one frame-number pattern, e.g. picture-%04d.png");
  return out;
}

int run(int argc, char** argv) {
  const cli::ToolSpec spec{
      "render", "RUN.h5|MESH.h5|- [options] -o PICTURE.png|.svg",
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
  cli::CommonOptions common;
  std::string input, colour, fragments, beams, range, view, format;
  long long frame = 0;
  double time = 0;
  bool all_frames = false, axes = false, no_title = false;
  long long every = 1;
  render::CanvasSize size;
  po::options_description desc("Options");
  desc.add_options()
      ("input", po::value(&input)->required(), "mesh or run file, or - for standard input")
      ("frame", po::value(&frame), "frame to draw: 0 the first, -1 the final state (default: the fragments' "
       "frame with --fragments, else -1)")
      ("time", po::value(&time), "draw the frame nearest to this time, in s")
      ("all-frames", po::bool_switch(&all_frames), "draw every frame; -o needs a frame-number pattern, e.g. "
       "picture-%04d.png (numbered 0, 1, 2, ... for a movie)")
      ("every", po::value(&every)->default_value(1), "with --all-frames: every N-th frame only")
      ("colour", po::value(&colour), "what colours cells or nodes: fragment, speed, strain, none, or a dataset or "
       "time series with one value per body (e.g. angle, angular_velocity, /particles/cells/area); default: "
       "fragment with --fragments, else speed (DEM run), strain (rubber run), none (mesh)")
      ("fragments", po::value(&fragments), "fragments file of this run (fragment-count) for --colour fragment")
      ("beams", po::value(&beams)->default_value("strain"), "beams or bonds: strain (coloured by strain relative to "
       "the breaking threshold, broken ones crossed), broken (only the broken ones), off")
      ("range", po::value(&range), "colour range of the cells' or nodes' field, MIN,MAX (default: the data's)")
      ("view", po::value(&view), "region shown, XMIN,YMIN,XMAX,YMAX in m (default: everything)")
      ("width", po::value(&size.width)->default_value(1000), "picture width in pixels")
      ("height", po::value(&size.height)->default_value(0), "picture height in pixels (0: from the view's aspect)")
      ("axes", po::bool_switch(&axes), "draw axes with ticks in metres")
      ("no-title", po::bool_switch(&no_title), "leave out the title line (file, frame, time)")
      ("format", po::value(&format), "png or svg (default: from the output's extension; png for standard output)");
  cli::add_common(desc, common, cli::kOutput | cli::kQuiet | cli::kConfig,
                  "picture file, .png or .svg (with --all-frames a frame-number pattern); '-' writes the PNG (or "
                  "--format svg) to standard output");
  po::positional_options_description positional;
  positional.add("input", 1);
  const auto vm = cli::parse(argc, argv, spec, desc, positional);
  const std::vector<FileRole> inputs{{"RUN", input}, {"--fragments", fragments}, {"--config", common.config}};
  if (!all_frames) check_file_roles(inputs, {{"-o", common.output}});

  const int choices = static_cast<int>(vm.count("frame")) + static_cast<int>(vm.count("time")) + (all_frames ? 1 : 0);
  if (choices > 1) throw UsageError("--frame, --time and --all-frames: give one of them");
  if (every < 1) throw UsageError("--every: must be at least 1, got " + std::to_string(every));
  if (size.width < 100 || size.width > 20000)
    throw UsageError("--width: between 100 and 20000 pixels, got " + std::to_string(size.width));
  if (size.height != 0 && (size.height < 100 || size.height > 20000))
    throw UsageError("--height: 0 (automatic) or between 100 and 20000 pixels, got " + std::to_string(size.height));
  if (vm.count("time") && !std::isfinite(time)) throw UsageError("--time: not a finite number");
  const render::ImageFormat fmt = vm.count("format") ? render::format_from_text(format)
                                  : common.output == "-" ? render::ImageFormat::png
                                                         : render::format_from_name(common.output);
  // (a name without an extension, such as /dev/null, takes --format's)
  if (vm.count("format") && std::filesystem::path(common.output).has_extension() &&
      render::format_from_name(common.output) != fmt)
    throw UsageError("--format " + format + " does not match the extension of '" + common.output + "'");
  if (all_frames && common.output == "-") throw UsageError("--all-frames: write to files (-o picture-%04d.png), not to standard output");
  if (all_frames) numbered(common.output, 0);  // checks the pattern before any work

  render::PictureOptions opt;
  opt.colour = colour;
  opt.links = beams;
  render::link_mode_from_text(beams);
  opt.axes = axes;
  opt.title = !no_title;
  opt.name = input == "-" ? "standard input" : "";
  if (vm.count("range")) {
    const auto r = parse_numbers(range, 2, "--range", "MIN,MAX");
    if (!(r[1] > r[0])) throw UsageError("--range: MAX must be above MIN, got '" + range + "'");
    opt.range = std::array<double, 2>{r[0], r[1]};
  }
  if (vm.count("view")) {
    const auto v = parse_numbers(view, 4, "--view", "XMIN,YMIN,XMAX,YMAX");
    if (!(v[2] > v[0] && v[3] > v[1])) throw UsageError("--view: XMAX must exceed XMIN and YMAX YMIN, got '" + view + "'");
    opt.view = std::array<double, 4>{v[0], v[1], v[2], v[3]};
  }

  const io::Group root = io::open_input(input);
  ToolRun run = start_run("render", cli::command_line(argc, argv));
  io::add_input(run, root);
  std::optional<io::Group> fragments_root;
  std::optional<render::FragmentLabels> labels;
  if (vm.count("fragments")) {
    fragments_root.emplace(io::open_input(fragments));
    io::add_input(run, *fragments_root);
    labels = render::read_fragment_labels(*fragments_root);
    if (!render::counted_from(*fragments_root, root) && !common.quiet)
      std::cerr << "render: warning: " << fragments << " was not counted from " << input
                << " (its provenance does not name that file)\n";
  }
  const std::string provenance = provenance_line(run);
  render::RunPicture picture(root, labels, opt);
  if (!picture.is_run() && choices > 0)
    throw UsageError(std::string(vm.count("frame") ? "--frame" : vm.count("time") ? "--time" : "--all-frames") +
                     ": " + input + " is a mesh file: it has no frames");

  auto say = [&](const std::string& text) {
    if (!common.quiet) std::cerr << "render: " << text << "\n";
  };
  if (!all_frames) {
    const long long k = vm.count("frame") ? picture.frame_index(frame)
                        : vm.count("time") ? picture.frame_at_time(time)
                                           : picture.default_frame();
    if (labels && picture.colour() == "fragment" && picture.is_run() && k != labels->frame)
      say("warning: the fragments were counted at frame " + std::to_string(labels->frame) + ", drawing frame " +
          std::to_string(k));
    const render::Figure fig = picture.figure(k);
    render::write_figure(fig, size, fmt, common.output, provenance);
    const auto px = render::canvas_pixels(fig, size);
    say("wrote " + (common.output == "-" ? std::string("standard output") : common.output) + " (" +
        std::to_string(px[0]) + "x" + std::to_string(px[1]) + (picture.is_run() ? ", frame " + std::to_string(k) : "") + ")");
    return kExitOk;
  }

  std::vector<long long> frames;
  for (long long k = 0; k < static_cast<long long>(picture.frames()); k += every) frames.push_back(k);
  picture.fix_across(frames);  // one view and one colour range for the whole sequence
  for (std::size_t s = 0; s < frames.size(); ++s) {
    check_file_roles(inputs, {{"-o", numbered(common.output, static_cast<long long>(s))}});
    render::write_figure(picture.figure(frames[s]), size, fmt, numbered(common.output, static_cast<long long>(s)),
                         provenance);
  }
  say("wrote " + std::to_string(frames.size()) + " pictures, " + numbered(common.output, 0) + " to " +
      numbered(common.output, static_cast<long long>(frames.size()) - 1));
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::run_tool("render", [&] { return run(argc, argv); });
}
