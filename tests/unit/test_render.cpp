// Pictures and XDMF sidecars: colour maps, the world transform of body-frame polygons, the figure of a
// hand-built run (beams coloured against t_eps, broken ones marked), PNG and SVG output, and the XDMF
// text of small mesh and run files (dataset paths, dimensions, hyperslabs).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>

#include "analysis/fragments.hpp"
#include "analysis/fragments_io.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/provenance_text.hpp"
#include "io/run_io.hpp"
#include "io/xdmf.hpp"
#include "render/canvas.hpp"
#include "render/colour.hpp"
#include "render/figure.hpp"
#include "render/run_picture.hpp"

namespace fs = std::filesystem;
using namespace frac;
using render::Rgb;
using render::Vec2;

namespace {

fs::path render_temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("fracture-test-render-" + name + "-" + make_uuid().substr(0, 8));
  fs::create_directories(dir);
  return dir;
}

void expect_rgb_near(const Rgb& a, const Rgb& b, double tol = 1e-9) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

mesh::CellMesh render_grid(int nx, int ny) { return mesh::make_square_grid(nx, ny); }

// A 2 x 2 DEM run of two frames with t_eps = 0.02: frame 0 the reference state at rest; frame 1 at
// t = 0.5 s with cell 3 turned by 45 degrees and moved by (0.25, 0), moving at (3, 4) m/s, beam 0
// (cells 0-1) at strain 0.02, beam 1 (0-2) at -0.01, beam 3 (2-3) broken.
struct SmallRun {
  mesh::CellMesh mesh = render_grid(2, 2);
  std::string path;
};

SmallRun write_small_run(const fs::path& dir, const std::function<void(io::BodyFrame&)>& spoil_frame_1 = {}) {
  SmallRun r;
  r.path = (dir / "run.h5").string();
  const auto& m = r.mesh;
  const std::size_t n = m.cells(), b = m.beams();
  std::vector<double> mass(n, 2.0), inertia(n, 0.3);
  io::OutputFile out(r.path);
  ToolRun run = start_run("dem-run", "dem-run --scene test.ini mesh.h5 -o run.h5");
  run.parameters = {{"material.t_eps", "0.02"}, {"material.density", "1000"}};
  io::write_header(out.root(), "run", run, out.uuid());
  io::RunWriter w(out.root(), m, mass, inertia);
  io::BodyFrame f;
  for (const auto& c : m.centroid) f.position.insert(f.position.end(), {c.x(), c.y()});
  f.velocity.assign(2 * n, 0.0);
  f.angle.assign(n, 0.0);
  f.angular_velocity.assign(n, 0.0);
  f.intact.assign(b, 1);
  f.strain.assign(b, 0.0);
  w.write_frame(f);
  f.step = 100;
  f.time = 0.5;
  f.position[6] += 0.25;
  f.angle[3] = std::numbers::pi / 4;
  f.velocity[6] = 3.0;
  f.velocity[7] = 4.0;
  f.strain[0] = 0.02;
  f.strain[1] = -0.01;
  f.intact[3] = 0;
  if (spoil_frame_1) spoil_frame_1(f);
  w.write_frame(f);
  w.finish();
  out.commit();
  return r;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (auto p = text.find(needle); p != std::string::npos; p = text.find(needle, p + needle.size())) ++count;
  return count;
}

}  // namespace

TEST(RenderColour, ViridisEndsMiddleAndClamping) {
  expect_rgb_near(render::viridis(0.0), {0.267004, 0.004874, 0.329415});
  expect_rgb_near(render::viridis(1.0), {0.993248, 0.906157, 0.143936});
  expect_rgb_near(render::viridis(0.5), {0.127568, 0.566949, 0.550556});
  // Halfway between two samples: their mean.
  expect_rgb_near(render::viridis(0.05),
                  {(0.267004 + 0.282623) / 2, (0.004874 + 0.140926) / 2, (0.329415 + 0.457517) / 2});
  EXPECT_EQ(render::viridis(-3.0), render::viridis(0.0));
  EXPECT_EQ(render::viridis(7.0), render::viridis(1.0));
  EXPECT_EQ(render::viridis(std::nan("")), render::viridis(0.0));
  // Luminance rises monotonically along viridis.
  double last = -1;
  for (int k = 0; k <= 20; ++k) {
    const Rgb c = render::viridis(k / 20.0);
    const double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(y, last) << k;
    last = y;
  }
}

TEST(RenderColour, CoolWarmIsNeutralInTheMiddle) {
  expect_rgb_near(render::coolwarm(0.5), {0.865, 0.865, 0.865});
  const Rgb cold = render::coolwarm(0.0), warm = render::coolwarm(1.0);
  EXPECT_GT(cold.b, cold.r);
  EXPECT_GT(warm.r, warm.b);
  EXPECT_EQ(render::sample(render::Palette::coolwarm, 0.25), render::coolwarm(0.25));
  EXPECT_EQ(render::hex(render::coolwarm(1.0)), "#b40426");
}

TEST(RenderColour, CategoriesAreDistinct) {
  EXPECT_EQ(render::category(-1), render::kDebrisGrey);
  EXPECT_EQ(render::hex(render::category(0)), "#1f77b4");
  std::vector<std::string> seen;
  for (int k = 0; k < 60; ++k) {
    const std::string h = render::hex(render::category(k));
    EXPECT_EQ(std::count(seen.begin(), seen.end(), h), 0) << "label " << k << " repeats " << h;
    EXPECT_NE(h, render::hex(render::kDebrisGrey));
    seen.push_back(h);
  }
}

TEST(RenderColour, ScaleNormalises) {
  render::ColourScale s{render::Palette::viridis, 2.0, 6.0, "speed (m/s)"};
  EXPECT_DOUBLE_EQ(s.normalise(4.0), 0.5);
  EXPECT_DOUBLE_EQ(s.normalise(1.0), 0.0);
  EXPECT_DOUBLE_EQ(s.normalise(9.0), 1.0);
  EXPECT_EQ(s(6.0), render::viridis(1.0));
  render::ColourScale empty{render::Palette::viridis, 3.0, 3.0, ""};
  EXPECT_DOUBLE_EQ(empty.normalise(3.0), 0.5);
}

TEST(RenderGeometry, WorldPolygonTurnsAboutTheCentroidThenMoves) {
  const std::vector<Vec2> body{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  const auto w = render::world_polygon(body, Vec2(2.0, 3.0), std::numbers::pi / 2);
  ASSERT_EQ(w.size(), 4u);
  // (x, y) turned by +90 degrees is (-y, x).
  EXPECT_NEAR(w[0].x(), 2.5, 1e-15);
  EXPECT_NEAR(w[0].y(), 2.5, 1e-15);
  EXPECT_NEAR(w[1].x(), 2.5, 1e-15);
  EXPECT_NEAR(w[1].y(), 3.5, 1e-15);
  EXPECT_NEAR(w[2].x(), 1.5, 1e-15);
  EXPECT_NEAR(w[2].y(), 3.5, 1e-15);
  // A general angle keeps distances to the centroid and the orientation (counter-clockwise).
  const std::vector<Vec2> tri{{0.3, -0.1}, {0.0, 0.4}, {-0.3, -0.3}};
  const auto t = render::world_polygon(tri, Vec2(-1.0, 0.5), 0.7);
  double area = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR((t[k] - Vec2(-1.0, 0.5)).norm(), tri[k].norm(), 1e-14);
    area += geometry::cross(t[k], t[(k + 1) % 3]);
  }
  EXPECT_GT(area, 0.0);
  const auto same = render::world_polygon(tri, Vec2(0, 0), 0.0);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(same[k], tri[k]);
}

TEST(RenderPicture, FrameOfASmallRun) {
  const auto dir = render_temp_dir("frame");
  const SmallRun r = write_small_run(dir);
  const io::Group root = io::open_input(r.path);
  const auto threshold = render::read_threshold(root, true);
  ASSERT_TRUE(threshold);
  EXPECT_DOUBLE_EQ(threshold->strain, 0.02);

  render::RunPicture picture(root, std::nullopt, {});
  EXPECT_TRUE(picture.is_run());
  EXPECT_EQ(picture.frames(), 2u);
  EXPECT_EQ(picture.colour(), "speed");
  EXPECT_EQ(picture.default_frame(), 1);
  EXPECT_EQ(picture.frame_index(-2), 0);
  EXPECT_EQ(picture.frame_at_time(0.4), 1);
  EXPECT_THROW(picture.frame_index(2), UsageError);

  const render::Figure f = picture.figure(1);
  ASSERT_EQ(f.polygons.size(), 4u);
  const auto expected = render::world_polygon(r.mesh.polygon(3), Vec2(1.75, 1.5), std::numbers::pi / 4);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR((f.polygons[3].vertex[k] - expected[k]).norm(), 0.0, 1e-14);
  // Speed: cell 3 at 5 m/s is the top of the range, the others at rest the bottom.
  ASSERT_EQ(f.colour_bars.size(), 2u);
  EXPECT_EQ(f.colour_bars[0].label, "speed (m/s)");
  EXPECT_DOUBLE_EQ(f.colour_bars[0].min, 0.0);
  EXPECT_DOUBLE_EQ(f.colour_bars[0].max, 5.0);
  EXPECT_EQ(f.polygons[3].fill, render::viridis(1.0));
  EXPECT_EQ(f.polygons[0].fill, render::viridis(0.0));
  // Beams: (0,1) (0,2) (1,3) (2,3); the broken one marked at the middle of its cells' positions.
  ASSERT_EQ(f.segments.size(), 3u);
  ASSERT_EQ(f.markers.size(), 1u);
  EXPECT_NEAR((f.markers[0] - Vec2(0.5 * (0.5 + 1.75), 1.5)).norm(), 0.0, 1e-14);
  EXPECT_EQ(f.segments[0].colour, render::coolwarm(1.0));   // strain = t_eps
  EXPECT_EQ(f.segments[1].colour, render::coolwarm(0.25));  // strain = -t_eps / 2
  EXPECT_EQ(f.segments[2].colour, render::coolwarm(0.5));   // unstrained
  EXPECT_NE(f.colour_bars[1].label.find("t_ε = 0.02"), std::string::npos) << f.colour_bars[1].label;
  EXPECT_NE(f.title.find("t = 0.5 s"), std::string::npos) << f.title;
  EXPECT_NE(f.title.find("1 broken beams"), std::string::npos) << f.title;

  // Only the broken beams; no beams at all.
  render::PictureOptions broken;
  broken.links = "broken";
  broken.colour = "angle";
  const render::Figure g = render::RunPicture(root, std::nullopt, broken).figure(1);
  EXPECT_TRUE(g.segments.empty());
  EXPECT_EQ(g.markers.size(), 1u);
  ASSERT_EQ(g.colour_bars.size(), 1u);
  EXPECT_EQ(g.colour_bars[0].label, "angle (rad)");
  EXPECT_EQ(g.polygons[3].fill, render::viridis(1.0));
  render::PictureOptions off;
  off.links = "off";
  off.colour = "/particles/cells/area";
  const render::Figure h = render::RunPicture(root, std::nullopt, off).figure(0);
  EXPECT_TRUE(h.segments.empty() && h.markers.empty());
  EXPECT_EQ(h.colour_bars.at(0).label, "area (m^2)");

  // Bad choices are refused with the option named.
  render::PictureOptions bad;
  bad.colour = "frobnicate";
  try {
    render::RunPicture(root, std::nullopt, bad);
    ADD_FAILURE() << "accepted --colour frobnicate";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--colour frobnicate"), std::string::npos) << e.what();
  }
  bad.colour = "fragment";
  EXPECT_THROW(render::RunPicture(root, std::nullopt, bad), UsageError);
  bad.colour = "vertex_offset";  // N + 1 values
  EXPECT_THROW(render::RunPicture(root, std::nullopt, bad), UsageError);
  EXPECT_THROW(render::link_mode_from_text("maybe"), UsageError);
  fs::remove_all(dir);
}

TEST(RenderPicture, RefusesACellAtANonFinitePositionOrAngle) {
  const auto dir = render_temp_dir("nan");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const bool angle : {false, true}) {
    const SmallRun r = write_small_run(dir, [&](io::BodyFrame& f) { (angle ? f.angle[2] : f.position[5]) = nan; });
    const io::Group root = io::open_input(r.path);
    const render::RunPicture picture(root, std::nullopt, {});
    EXPECT_NO_THROW(picture.figure(0));
    const std::string expected = r.path +
                                 (angle ? ":/particles/cells/angle: frame 1 (t = 0.5 s): cell 2: angle nan"
                                        : ":/particles/cells/position: frame 1 (t = 0.5 s): cell 2: (0.5, nan)") +
                                 " is not finite";
    try {
      picture.figure(1);
      ADD_FAILURE() << "drew a frame holding a NaN";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
  fs::remove_all(dir);
}

TEST(RenderPicture, FragmentsColourCells) {
  const auto dir = render_temp_dir("fragments");
  const SmallRun r = write_small_run(dir);
  const auto frags_path = (dir / "fragments.h5").string();
  {
    const io::Group root = io::open_input(r.path);
    const io::RunInfo info = analysis::read_dem_run_info(root);
    const analysis::FragmentInput in = analysis::read_fragment_input(root, info, 1);
    analysis::FragmentRecord rec;
    rec.frame = 1;
    rec.step = in.step;
    rec.time = in.time;
    rec.fragments = analysis::find_fragments(in.state());
    io::OutputFile out(frags_path);
    io::write_header(out.root(), "fragments", start_run("fragment-count", "fragment-count run.h5"), out.uuid());
    analysis::write_fragments(out.root(), rec);
    out.commit();
  }
  const io::Group root = io::open_input(r.path);
  const io::Group frags = io::open_input(frags_path);
  const auto labels = render::read_fragment_labels(frags);
  EXPECT_EQ(labels.frame, 1);
  render::RunPicture picture(root, labels, {});
  EXPECT_EQ(picture.colour(), "fragment");
  const render::Figure f = picture.figure(picture.default_frame());
  // Beam 2-3 broken only: one fragment of all four cells.
  ASSERT_EQ(labels.mass.size(), 1u);
  for (const auto& p : f.polygons) EXPECT_EQ(p.fill, render::category(0));
  ASSERT_FALSE(f.legend.empty());
  EXPECT_NE(f.legend[0].text.find("4 cells"), std::string::npos) << f.legend[0].text;
  // Labels for another mesh are refused, naming the dataset.
  const auto other = (dir / "other.h5").string();
  {
    io::OutputFile out(other);
    io::write_header(out.root(), "mesh", start_run("mesh-gen", "mesh-gen"), out.uuid());
    io::write_mesh(out.root(), render_grid(3, 2));
    out.commit();
  }
  const io::Group mesh_root = io::open_input(other);
  try {
    render::RunPicture(mesh_root, labels, {});
    ADD_FAILURE() << "accepted labels of 4 cells for 6";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/fragments/cell_fragment"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(RenderCanvas, WritesPngAndSvgAtomically) {
  const auto dir = render_temp_dir("canvas");
  const SmallRun r = write_small_run(dir);
  const io::Group root = io::open_input(r.path);
  render::PictureOptions opt;
  opt.axes = true;
  const render::Figure f = render::RunPicture(root, std::nullopt, opt).figure(1);
  const render::CanvasSize size{400, 0};
  const auto px = render::canvas_pixels(f, size);
  EXPECT_EQ(px[0], 400);
  EXPECT_EQ(px[1] % 2, 0);  // even, for video encoders

  const auto png = (dir / "picture.png").string();
  render::write_figure(f, size, render::format_from_name(png), png, "tool=test command=a<b");
  const std::string bytes = read_text(png);
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 3]));
  };
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(16), static_cast<unsigned>(px[0]));
  EXPECT_EQ(be32(20), static_cast<unsigned>(px[1]));
  EXPECT_EQ(bytes.substr(37, 4), "tEXt");  // the provenance, right after IHDR
  EXPECT_EQ(bytes.substr(41, be32(33)), std::string("provenance\0tool=test command=a<b", 32));

  const auto svg = (dir / "picture.svg").string();
  render::write_figure(f, {400, 300}, render::format_from_name(svg), svg, "tool=test command=a<b");
  const std::string text = read_text(svg);
  EXPECT_EQ(text.rfind("<?xml", 0), 0u);
  EXPECT_NE(text.find("<metadata id=\"provenance\">tool=test command=a&lt;b</metadata>"), std::string::npos);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("width=\"400"), std::string::npos);
  EXPECT_GE(count_of(text, "<path"), 4u);  // at least the four cells

  // Nothing but the run and the two pictures in the folder: no temporary file left behind.
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 3u);
  EXPECT_THROW(render::write_figure(f, size, render::ImageFormat::png, (dir / "missing" / "x.png").string(), ""),
               UsageError);
  EXPECT_THROW(render::format_from_name("picture.jpg"), UsageError);
  EXPECT_THROW(render::format_from_text("gif"), UsageError);
  EXPECT_EQ(render::format_from_name("A.SVG"), render::ImageFormat::svg);
  fs::remove_all(dir);
}

TEST(Provenance, LineAndItsPlaceInPngSvgCsv) {
  ToolRun run = start_run("render", "render 'a b.h5'\n-o x.png");
  run.input_uuids = {"u1", "u2"};
  const std::string line = provenance_line(run);
  EXPECT_EQ(line.rfind("tool=render version=", 0), 0u);
  EXPECT_NE(line.find(" time=" + run.started + " inputs=u1,u2 command=render 'a b.h5'\\n-o x.png"), std::string::npos);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  EXPECT_EQ(line.find("seed="), std::string::npos);
  run.seed = "7";
  EXPECT_NE(provenance_line(run).find(" seed=7 inputs="), std::string::npos);

  // A PNG of IHDR and IEND only: the text chunk goes between them, with its length and the CRC-32 of its
  // type and data (as Python's zlib.crc32 gives it).
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  const std::string ihdr = std::string("\0\0\0\x0dIHDR", 8) + std::string(13, '\1') + "CRC!";
  const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  const std::string png = io::png_with_text(signature + ihdr + iend, "k", "ab");
  EXPECT_EQ(png.substr(0, 33), signature + ihdr);
  EXPECT_EQ(png.substr(33, 16), std::string("\0\0\0\x04tEXtk\0ab\x84\xf9\xfc\xd8", 16));
  EXPECT_EQ(png.substr(49), iend);
  // Not ASCII: iTXt (UTF-8), no compression, no language.
  const std::string utf8 = io::png_with_text(signature + ihdr + iend, "k", "\xc3\xa9");
  EXPECT_EQ(utf8.substr(37, 4), "iTXt");
  EXPECT_EQ(utf8.substr(41, 8), std::string("k\0\0\0\0\0\xc3\xa9", 8));
  EXPECT_THROW(io::png_with_text("GIF89a", "k", "x"), RuntimeError);

  EXPECT_EQ(io::svg_with_metadata("<?xml version=\"1.0\"?>\n<svg width=\"4\">\n<g/>\n</svg>\n", "a&\"b\""),
            "<?xml version=\"1.0\"?>\n<svg width=\"4\">\n<metadata "
            "id=\"provenance\">a&amp;&quot;b&quot;</metadata>\n<g/>\n</svg>\n");
  EXPECT_THROW(io::svg_with_metadata("<html/>", "x"), RuntimeError);
  EXPECT_EQ(io::csv_comment("tool=x"), "# tool=x\n");
}

TEST(Xdmf, RunSidecarReferencesTheDatasets) {
  const auto dir = render_temp_dir("xdmf-run");
  const SmallRun r = write_small_run(dir);
  const io::Group root = io::open_input(r.path);
  io::XdmfOptions opt;
  opt.data_file = io::relative_reference(r.path, (dir / "run.xmf").string());
  EXPECT_EQ(opt.data_file, "run.h5");
  io::XdmfReport report;
  const std::string x = io::xdmf_document(root, opt, &report);
  EXPECT_EQ(report.bodies, 4u);
  EXPECT_EQ(report.links, 4u);
  EXPECT_EQ(report.frames, 2u);
  EXPECT_EQ(report.polygon_vertices, 16u);

  EXPECT_EQ(x.rfind("<?xml version=\"1.0\"", 0), 0u);
  EXPECT_NE(x.find("<Xdmf Version=\"3.0\""), std::string::npos);
  // A temporal collection of two frames for the polygons, the cells and the beams.
  EXPECT_EQ(count_of(x, "CollectionType=\"Temporal\""), 3u);
  EXPECT_EQ(count_of(x, "<Time Value=\"0\"/>"), 3u);
  EXPECT_EQ(count_of(x, "<Time Value=\"0.5\"/>"), 3u);
  // Geometry: frame k of position/value [2,4,2], in the Xdmf 3 selection syntax.
  EXPECT_EQ(count_of(x,
                     "<DataItem Dimensions=\"4 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                     "run.h5:/particles/cells/position/value|1 0 0:1 1 1:1 4 2:2 4 2</DataItem>"),
            2u);
  EXPECT_EQ(count_of(x, "run.h5:/particles/cells/position/value|0 0 0:1 1 1:1 4 2:2 4 2</DataItem>"), 2u);
  EXPECT_EQ(x.find("HyperSlab"), std::string::npos);
  // Per-frame attributes: velocity (vector), angle, angular_velocity; beam strain and intact flags.
  for (const char* name : {"velocity", "angle", "angular_velocity", "strain", "intact"})
    EXPECT_NE(x.find("<Attribute Name=\"" + std::string(name) + "\""), std::string::npos) << name;
  EXPECT_NE(x.find("<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">"), std::string::npos);
  EXPECT_NE(x.find("Dimensions=\"4\" NumberType=\"Float\" Precision=\"8\" "
                   "Format=\"HDF\">run.h5:/particles/cells/angle/value|1 0:1 1:1 4:2 4<"),
            std::string::npos);
  EXPECT_NE(x.find("Dimensions=\"4\" NumberType=\"UChar\" Precision=\"1\" "
                   "Format=\"HDF\">run.h5:/connectivity/beams/trajectory/intact/value|0 0:1 1:1 4:2 4<"),
            std::string::npos);
  EXPECT_NE(x.find("run.h5:/connectivity/beams/trajectory/strain/value|1 0:1 1:1 4:2 4<"), std::string::npos);
  // Static data: mass, inertia, area; the beams' pairs as two-point polylines.
  EXPECT_NE(
      x.find("Dimensions=\"4\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">run.h5:/particles/cells/mass<"),
      std::string::npos);
  EXPECT_NE(x.find("<Topology TopologyType=\"Polyline\" NumberOfElements=\"4\" NodesPerElement=\"2\">"),
            std::string::npos);
  EXPECT_NE(
      x.find("Dimensions=\"4 2\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">run.h5:/connectivity/beams/pairs<"),
      std::string::npos);
  // The points' topology is shared by XInclude: the first element of the Domain.
  EXPECT_NE(
      x.find(
          "<Domain Name=\"run.h5\">\n    <Topology Name=\"points\" TopologyType=\"Polyvertex\" NumberOfElements=\"4\" "
          "NodesPerElement=\"1\">\n      <DataItem Dimensions=\"4\" NumberType=\"Int\" Precision=\"8\" "
          "Format=\"XML\">\n0 1 2 3\n"),
      std::string::npos);
  EXPECT_EQ(count_of(x, "<xi:include xpointer=\"element(/1/1/1)\"/>"), 2u);
  // The reference polygons inline, shared by the polygon grid of every frame: a Mixed topology of
  // Polygon (3) elements and its geometry, the second and third elements of the Domain.
  EXPECT_NE(
      x.find("</Topology>\n    <Topology Name=\"reference_polygons\" TopologyType=\"Mixed\" NumberOfElements=\"4\">"),
      std::string::npos);
  EXPECT_NE(x.find("</Topology>\n    <Geometry Name=\"reference_polygons\" GeometryType=\"XY\">"), std::string::npos);
  EXPECT_EQ(count_of(x, "<xi:include xpointer=\"element(/1/1/2)\"/>"), 2u);
  EXPECT_EQ(count_of(x, "<xi:include xpointer=\"element(/1/1/3)\"/>"), 2u);
  EXPECT_EQ(count_of(x, "<Attribute Name=\"area\" AttributeType=\"Scalar\" Center=\"Cell\">"), 2u);
  EXPECT_NE(x.find("<DataItem Dimensions=\"24\" NumberType=\"Int\" Precision=\"8\" Format=\"XML\">\n3 4 0 1 2 3\n"),
            std::string::npos);
  EXPECT_NE(
      x.find(
          "<DataItem Dimensions=\"16 2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">\n0 0\n1 0\n1 1\n0 1\n"),
      std::string::npos);
  // Never the vertex offsets or the position series as attributes.
  EXPECT_EQ(x.find("Name=\"vertex_offset\""), std::string::npos);
  EXPECT_EQ(x.find("Name=\"position\""), std::string::npos);

  // XDMF 2: HyperSlab DataItems of the specification.
  opt.flavour = io::XdmfFlavour::xdmf2;
  const std::string v2 = io::xdmf_document(root, opt);
  EXPECT_NE(v2.find("<Xdmf Version=\"2.0\""), std::string::npos);
  EXPECT_EQ(count_of(v2, "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"4 2\">"), 6u);  // + velocity
  EXPECT_NE(v2.find(">1 0 0  1 1 1  1 4 2</DataItem>"), std::string::npos);
  EXPECT_EQ(count_of(v2,
                     "<DataItem Dimensions=\"2 4 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                     "run.h5:/particles/cells/position/value</DataItem>"),
            4u);
  opt.flavour = io::XdmfFlavour::xdmf3;

  // Without polygons; a reference from another folder.
  opt.polygons = io::XdmfPolygons::off;
  opt.data_file = io::relative_reference(r.path, (dir / "sub" / "run.xmf").string());
  EXPECT_EQ(opt.data_file, "../run.h5");
  const std::string y = io::xdmf_document(root, opt);
  EXPECT_EQ(y.find("TopologyType=\"Mixed\""), std::string::npos);
  EXPECT_NE(y.find("../run.h5:/particles/cells/position/value"), std::string::npos);
  opt.polygons = io::XdmfPolygons::automatic;
  opt.inline_vertex_limit = 10;
  io::XdmfReport limited;
  const std::string z = io::xdmf_document(root, opt, &limited);
  EXPECT_EQ(z.find("TopologyType=\"Mixed\""), std::string::npos);
  ASSERT_EQ(limited.notes.size(), 1u);
  EXPECT_NE(limited.notes[0].find("16 vertices"), std::string::npos) << limited.notes[0];
  fs::remove_all(dir);
}

TEST(Xdmf, MeshSidecarAndFragments) {
  const auto dir = render_temp_dir("xdmf-mesh");
  const auto path = (dir / "mesh.h5").string();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", start_run("mesh-gen", "mesh-gen"), out.uuid());
    io::write_mesh(out.root(), render_grid(3, 2));
    out.commit();
  }
  const io::Group root = io::open_input(path);
  io::XdmfOptions opt;
  opt.data_file = "mesh.h5";
  const std::string x = io::xdmf_document(root, opt);
  EXPECT_EQ(x.find("Temporal"), std::string::npos);
  EXPECT_EQ(x.find("<Time"), std::string::npos);
  EXPECT_NE(x.find("<Grid Name=\"cells\" GridType=\"Uniform\">"), std::string::npos);
  EXPECT_NE(x.find("<Grid Name=\"beams\" GridType=\"Uniform\">"), std::string::npos);
  EXPECT_NE(x.find("<Topology TopologyType=\"Polyline\" NumberOfElements=\"7\" NodesPerElement=\"2\">"),
            std::string::npos);
  EXPECT_NE(
      x.find(
          "Dimensions=\"6 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">mesh.h5:/particles/cells/centroid<"),
      std::string::npos);
  EXPECT_NE(x.find("mesh.h5:/connectivity/beams/length<"), std::string::npos);
  EXPECT_NE(x.find("mesh.h5:/connectivity/beams/section<"), std::string::npos);
  EXPECT_NE(x.find("mesh.h5:/particles/cells/second_moment<"), std::string::npos);

  // A fragments file of the right size adds the cell attribute; one of another size is refused.
  auto write_fragments = [&](const std::string& p, std::size_t cells) {
    io::OutputFile out(p);
    io::write_header(out.root(), "fragments", start_run("fragment-count", "fragment-count"), out.uuid());
    analysis::FragmentRecord rec;
    rec.fragments.cell_fragment.assign(cells, 0);
    rec.fragments.mass = {static_cast<double>(cells)};
    rec.fragments.cell_count = {static_cast<std::int64_t>(cells)};
    rec.fragments.center_of_mass = {0, 0};
    rec.fragments.velocity = {0, 0};
    rec.fragments.kinetic_energy_translational = {0};
    rec.fragments.kinetic_energy_rotational = {0};
    analysis::write_fragments(out.root(), rec);
    out.commit();
  };
  write_fragments((dir / "f6.h5").string(), 6);
  write_fragments((dir / "f5.h5").string(), 5);
  const io::Group f6 = io::open_input((dir / "f6.h5").string());
  opt.fragments = &f6;
  opt.fragments_file = "f6.h5";
  const std::string y = io::xdmf_document(root, opt);
  EXPECT_NE(y.find("<Attribute Name=\"fragment\" AttributeType=\"Scalar\" Center=\"Cell\">"), std::string::npos);
  EXPECT_NE(
      y.find("Dimensions=\"6\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">f6.h5:/fragments/cell_fragment<"),
      std::string::npos);
  const io::Group f5 = io::open_input((dir / "f5.h5").string());
  opt.fragments = &f5;
  EXPECT_THROW(io::xdmf_document(root, opt), InputError);

  // Text files appear whole or not at all.
  const auto xmf = (dir / "mesh.xmf").string();
  io::write_text_file(xmf, x);
  EXPECT_EQ(read_text(xmf), x);
  EXPECT_THROW(io::write_text_file((dir / "missing" / "m.xmf").string(), x), UsageError);
  std::size_t temps = 0;
  for (const auto& e : fs::directory_iterator(dir))
    temps += e.path().filename().string().find(".tmp-") != std::string::npos;
  EXPECT_EQ(temps, 0u);
  fs::remove_all(dir);
}
