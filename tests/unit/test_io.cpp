// The HDF5 layer: round trips of both meshes, header checks, provenance lineage, atomic output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/series.hpp"
#include "mesh/triangular_lattice.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace frac;
using frac::test::temp_dir;

namespace {

mesh::CellMesh two_squares() {
  // Two unit squares side by side, sharing the side x = 1: one beam of length 1 and section 1.
  mesh::CellMesh m;
  for (int k = 0; k < 2; ++k) {
    for (auto v : {mesh::Vec2(-0.5, -0.5), mesh::Vec2(0.5, -0.5), mesh::Vec2(0.5, 0.5), mesh::Vec2(-0.5, 0.5)})
      m.vertex.push_back(v);
    m.vertex_offset.push_back(m.vertex_offset.back() + 4);
    m.centroid.emplace_back(0.5 + k, 0.5);
    m.area.push_back(1.0);
    m.second_moment.push_back(1.0 / 6.0);
  }
  m.beam = {{0, 1}};
  m.beam_length = {1.0};
  m.beam_section = {1.0};
  m.shape = "rect";
  m.spacing = 1.0;
  m.disorder = 0.0;
  m.bounds = {0, 0, 2, 1};
  return m;
}

ToolRun test_run() {
  ToolRun run = start_run("test-tool", "test-tool --x 1");
  run.parameters = {{"x", "1"}};
  run.seed = "42";
  return run;
}

}  // namespace

TEST(Io, CellMeshRoundTrip) {
  const auto dir = temp_dir("cells");
  const auto path = (dir / "m.h5").string();
  const auto m = two_squares();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::write_mesh(out.root(), m);
    out.commit();
  }
  const auto root = io::open_input(path);
  EXPECT_EQ(io::check_header(root, {"mesh"}), "mesh");
  ASSERT_EQ(io::mesh_kind(root), io::MeshKind::cells);
  const auto r = io::read_cell_mesh(root);
  EXPECT_EQ(r.vertex_offset, m.vertex_offset);
  EXPECT_EQ(r.vertex, m.vertex);
  EXPECT_EQ(r.centroid, m.centroid);
  EXPECT_EQ(r.area, m.area);
  EXPECT_EQ(r.second_moment, m.second_moment);
  EXPECT_EQ(r.beam, m.beam);
  EXPECT_EQ(r.beam_length, m.beam_length);
  EXPECT_EQ(r.beam_section, m.beam_section);
  EXPECT_EQ(r.shape, "rect");
  EXPECT_EQ(r.bounds, m.bounds);
  EXPECT_EQ(root.attr_string("unit", "particles/cells/area"), "m^2");
  fs::remove_all(dir);
}

TEST(Io, NodeMeshRoundTrip) {
  const auto dir = temp_dir("nodes");
  const auto path = (dir / "n.h5").string();
  mesh::NodeMesh m;
  m.position = {{0, 0}, {1, 0}, {0.5, 0.8660254037844386}, {1.5, 0.8660254037844386}};
  m.nx = 2, m.ny = 2, m.spacing = 1.0;
  m.bond = {{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}};
  m.bond_length.assign(5, 1.0);
  m.intact = {1, 1, 0, 1, 1};
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::write_mesh(out.root(), m);
    out.commit();
  }
  const auto root = io::open_input(path);
  ASSERT_EQ(io::mesh_kind(root), io::MeshKind::nodes);
  const auto r = io::read_node_mesh(root);
  EXPECT_EQ(r.position, m.position);
  EXPECT_EQ(r.bond, m.bond);
  EXPECT_EQ(r.intact, m.intact);
  EXPECT_EQ(r.nx, 2);
  fs::remove_all(dir);
}

TEST(Io, ProvenanceCarriesTheLineage) {
  const auto dir = temp_dir("prov");
  const auto first = (dir / "first.h5").string(), second = (dir / "second.h5").string();
  std::string first_uuid;
  {
    io::OutputFile out(first);
    first_uuid = out.uuid();
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    out.commit();
  }
  {
    ToolRun run = start_run("second-tool", "second-tool first.h5");
    io::add_input(run, io::open_input(first));
    io::OutputFile out(second);
    io::write_header(out.root(), "mesh", run, out.uuid());
    out.commit();
  }
  const auto prov = io::read_provenance(io::open_input(second));
  ASSERT_EQ(prov.history.size(), 2u);
  EXPECT_EQ(prov.history[0].tool, "second-tool");  // newest first
  EXPECT_EQ(prov.history[0].file_uuid, prov.file_uuid);
  EXPECT_EQ(prov.history[1].tool, "test-tool");
  EXPECT_EQ(prov.history[1].file_uuid, first_uuid);
  EXPECT_EQ(prov.history[1].seed, "42");
  EXPECT_EQ(io::open_input(second).read_strings("provenance/inputs"), std::vector<std::string>{first_uuid});
  fs::remove_all(dir);
}

TEST(Io, OutputAppearsOnlyOnCommit) {
  const auto dir = temp_dir("atomic");
  const auto path = dir / "out.h5";
  {
    io::OutputFile out(path.string());
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    EXPECT_FALSE(fs::exists(path));  // written under a temporary name
    // No commit: as if the tool failed half way.
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir)) << "temporary file left behind";
  {
    io::OutputFile out(path.string());
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    out.commit();
  }
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

// Series are written a chunk at a time (io/series.hpp): every frame appended comes back, in order, whether
// it crossed a chunk boundary, sat in a partly filled chunk or waited in the buffer until flush().
TEST(Io, SeriesWriteEveryFrameAcrossChunks) {
  const auto dir = temp_dir("series");
  const auto path = (dir / "s.h5").string();
  // 20000 values a frame: 3 frames a chunk; scalars: 1024 a chunk; 2500 bytes a frame: 26 a chunk; 70000
  // values a frame: a chunk each (written at once).
  const std::size_t big = 20000, bytes = 2500, big_frames = 7, scalars = 2500, byte_frames = 30;
  const std::size_t huge = 70000, huge_frames = 3;
  auto big_value = [](std::size_t f, std::size_t k) { return 1e-3 * static_cast<double>(f) + static_cast<double>(k); };
  auto byte_value = [](std::size_t f, std::size_t k) { return static_cast<std::uint8_t>((f * 7 + k) % 251); };
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::SeriesWriter a(out.root(), "big", {big / 2, 2}, "m");
    io::SeriesWriter b(out.root(), "scalar", {}, "J");
    io::SeriesWriter c(out.root(), "bytes", {bytes}, "", io::SeriesType::uint8);
    io::SeriesWriter d(out.root(), "huge", {huge}, "m");
    std::vector<double> huge_frame(huge);
    for (std::size_t f = 0; f < huge_frames; ++f) {
      for (std::size_t k = 0; k < huge; ++k) huge_frame[k] = big_value(f + 100, k);
      d.append(static_cast<std::int64_t>(f), 0.0, std::span<const double>(huge_frame));
    }
    std::vector<double> frame(big);
    std::vector<std::uint8_t> byte_frame(bytes);
    for (std::size_t f = 0; f < big_frames; ++f) {
      for (std::size_t k = 0; k < big; ++k) frame[k] = big_value(f, k);
      a.append(static_cast<std::int64_t>(10 * f), 0.5 * static_cast<double>(f), std::span<const double>(frame));
    }
    for (std::size_t f = 0; f < scalars; ++f) {
      const double v = std::sqrt(static_cast<double>(f));
      b.append(static_cast<std::int64_t>(f), static_cast<double>(f), std::span<const double>(&v, 1));
    }
    for (std::size_t f = 0; f < byte_frames; ++f) {
      for (std::size_t k = 0; k < bytes; ++k) byte_frame[k] = byte_value(f, k);
      c.append(static_cast<std::int64_t>(f), 0.0, std::span<const std::uint8_t>(byte_frame));
    }
    EXPECT_EQ(a.frames(), big_frames);
    a.flush();
    b.flush();
    c.flush();
    d.flush();
    out.commit();
  }
  const auto root = io::open_input(path);
  const auto info = io::read_series_info(root, "big");
  ASSERT_EQ(info.step.size(), big_frames);
  EXPECT_EQ(info.frame_dims, (std::vector<hsize_t>{big / 2, 2}));
  for (std::size_t f = 0; f < big_frames; ++f) {
    EXPECT_EQ(info.step[f], static_cast<std::int64_t>(10 * f));
    EXPECT_EQ(info.time[f], 0.5 * static_cast<double>(f));
    const auto v = io::read_series_frame<double>(root, "big", static_cast<long long>(f));
    ASSERT_EQ(v.size(), big);
    for (std::size_t k = 0; k < big; ++k) ASSERT_EQ(v[k], big_value(f, k)) << "frame " << f << " value " << k;
  }
  const auto s = io::read_series_info(root, "scalar");
  ASSERT_EQ(s.step.size(), scalars);
  const auto all = root.group("scalar").read<double>("value", nullptr, 1);
  ASSERT_EQ(all.size(), scalars);
  for (std::size_t f = 0; f < scalars; ++f) {
    ASSERT_EQ(s.step[f], static_cast<std::int64_t>(f));
    ASSERT_EQ(all[f], std::sqrt(static_cast<double>(f))) << "row " << f;
  }
  ASSERT_EQ(io::read_series_info(root, "huge").step.size(), huge_frames);
  for (std::size_t f = 0; f < huge_frames; ++f) {
    const auto v = io::read_series_frame<double>(root, "huge", static_cast<long long>(f));
    ASSERT_EQ(v.size(), huge);
    for (std::size_t k = 0; k < huge; ++k) ASSERT_EQ(v[k], big_value(f + 100, k)) << "frame " << f;
  }
  for (std::size_t f = 0; f < byte_frames; ++f) {
    const auto v = io::read_series_frame<std::uint8_t>(root, "bytes", static_cast<long long>(f));
    ASSERT_EQ(v.size(), bytes);
    for (std::size_t k = 0; k < bytes; ++k) ASSERT_EQ(v[k], byte_value(f, k)) << "frame " << f;
  }
  fs::remove_all(dir);
}

// A compressed series flushed in the middle of a chunk (the chunk is written, padded, then written again
// whole when more frames come) reads back every frame, through HDF5's own shuffle and deflate filters.
TEST(Io, SeriesFlushedMidChunkReadsBackThroughTheDatasetsFilters) {
  const auto dir = temp_dir("series-flush");
  const auto path = (dir / "s.h5").string();
  const std::size_t values = 1000, frames = 150;  // 65 frames a chunk: three chunks, the last partly filled
  auto value = [](std::size_t f, std::size_t k) { return std::sin(1e-3 * static_cast<double>(f * values + k)); };
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::SeriesWriter a(out.root(), "a", {values}, "m");
    std::vector<double> frame(values);
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t k = 0; k < values; ++k) frame[k] = value(f, k);
      a.append(static_cast<std::int64_t>(f), static_cast<double>(f), std::span<const double>(frame));
      if (f == 1 || f == 2 || f == 70 || f == 140) a.flush();  // mid-chunk, twice in a row, in later chunks
    }
    a.flush();
    out.commit();
  }
  const auto root = io::open_input(path);
  ASSERT_EQ(io::read_series_info(root, "a").step.size(), frames);
  const auto all = root.group("a").read<double>("value", nullptr, 2);
  ASSERT_EQ(all.size(), frames * values);
  for (std::size_t f = 0; f < frames; ++f)
    for (std::size_t k = 0; k < values; ++k) ASSERT_EQ(all[f * values + k], value(f, k)) << "frame " << f;
  // The dataset's pipeline is HDF5's shuffle, then deflate: what any reader decodes the chunks with.
  io::Hid d(H5Dopen2(root.group("a").id(), "value", H5P_DEFAULT));
  io::Hid dcpl(H5Dget_create_plist(d.get()));
  ASSERT_EQ(H5Pget_nfilters(dcpl.get()), 2);
  unsigned flags = 0;
  std::size_t cd_count = 0;
  EXPECT_EQ(H5Pget_filter2(dcpl.get(), 0, &flags, &cd_count, nullptr, 0, nullptr, nullptr), H5Z_FILTER_SHUFFLE);
  cd_count = 0;
  EXPECT_EQ(H5Pget_filter2(dcpl.get(), 1, &flags, &cd_count, nullptr, 0, nullptr, nullptr), H5Z_FILTER_DEFLATE);
  fs::remove_all(dir);
}

TEST(Io, RefusesUnknownVersionKindAndMissingMesh) {
  const auto dir = temp_dir("refuse");
  const auto path = (dir / "v.h5").string();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "fit", test_run(), out.uuid());
    out.root().set_attr("format_version", std::vector<std::int64_t>{7, 3});
    out.commit();
  }
  const auto root = io::open_input(path);
  try {
    io::check_header(root, {"mesh"});
    FAIL() << "accepted format version 7.3";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("format version 7.3 is not supported"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::mesh_kind(root), InputError);
  EXPECT_THROW(io::open_input((dir / "missing.h5").string()), InputError);
  EXPECT_THROW(root.read<double>("particles/cells/area"), InputError);
  fs::remove_all(dir);
}

TEST(Io, ReadingChecksShapesAndNamesTheDataset) {
  const auto dir = temp_dir("shapes");
  const auto path = (dir / "s.h5").string();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::write_mesh(out.root(), two_squares());
    // Replace the areas by a dataset one row too long.
    H5Ldelete(out.root().id(), "particles/cells/area", H5P_DEFAULT);
    const std::vector<double> three{1.0, 1.0, 1.0};
    out.root().write("particles/cells/area", std::span<const double>(three), {3}, "m^2");
    out.commit();
  }
  try {
    io::read_cell_mesh(io::open_input(path));
    FAIL() << "accepted an area dataset of the wrong length";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/particles/cells/area"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Io, ReadersEnforceTheMeshInvariantsNamingTheFileAndCell) {
  const auto dir = temp_dir("invariants");
  const auto path = (dir / "m.h5").string();
  {
    auto m = two_squares();
    m.second_moment[1] = std::nan("");  // would pass every "differs by more than" test
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::write_mesh(out.root(), m);
    out.commit();
  }
  const io::Group root = io::open_input(path);
  try {
    io::read_cell_mesh(root);
    FAIL() << "accepted a NaN second moment";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": invalid mesh: finite: cell 1: second_moment is not finite");
  }
  // mesh-gen check's path: the mesh as stored, for its full report.
  EXPECT_TRUE(std::isnan(io::read_cell_mesh_as_stored(root).second_moment[1]));
  fs::remove_all(dir);
}

TEST(Io, NodeCountsFromTheFileCannotOverflow) {
  const auto dir = temp_dir("overflow");
  const auto path = (dir / "n.h5").string();
  {
    auto m = mesh::make_triangular_lattice({4, 3, 1e-3, "x", 0.0});
    m.nx = std::int64_t{1} << 62;  // times ny = 4 wraps to 0 in 64 bits
    m.ny = 4;
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    io::write_mesh(out.root(), m);
    out.commit();
  }
  try {
    io::read_node_mesh_as_stored(io::open_input(path));
    FAIL() << "accepted nx * ny that overflows";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("reference_position: has 12 rows, but the attributes say nx = 4611686018427387904"),
        std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

// Datasets of 64 Ki values or more are chunked and compressed, their chunks encoded by io/chunk_codec: every
// value reads back through HDF5's filters, in a last chunk that is full and in one that is not.
TEST(Io, LargeDatasetsReadBackExactly) {
  const auto dir = temp_dir("large");
  const auto path = (dir / "l.h5").string();
  const std::size_t rows = 100003;  // rows of 2 doubles: 32768 rows a chunk, the last chunk partly filled
  std::vector<double> xy(2 * rows);
  std::vector<std::int64_t> ids(65536 * 2);  // two full chunks
  std::vector<std::uint8_t> flags(70001);
  for (std::size_t k = 0; k < xy.size(); ++k) xy[k] = std::cos(0.37 * static_cast<double>(k)) * 1e-2;
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = static_cast<std::int64_t>(k * k) - 1000;
  for (std::size_t k = 0; k < flags.size(); ++k) flags[k] = static_cast<std::uint8_t>(k % 7 == 0);
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    out.root().write("xy", std::span<const double>(xy), {rows, 2}, "m");
    out.root().write("ids", std::span<const std::int64_t>(ids), {ids.size()});
    out.root().write("flags", std::span<const std::uint8_t>(flags), {flags.size()});
    out.commit();
  }
  const auto root = io::open_input(path);
  EXPECT_EQ(root.read<double>("xy", nullptr, 2), xy);
  EXPECT_EQ(root.read<std::int64_t>("ids", nullptr, 1), ids);
  EXPECT_EQ(root.read<std::uint8_t>("flags", nullptr, 1), flags);
  fs::remove_all(dir);
}

TEST(Io, WriteRefusesDataThatDoesNotMatchItsShape) {
  const auto dir = temp_dir("mismatch");
  io::OutputFile out((dir / "x.h5").string());
  const std::vector<double> three{1.0, 2.0, 3.0};
  EXPECT_THROW(out.root().write("x", std::span<const double>(three), {2}), RuntimeError);
  fs::remove_all(dir);
}

// A damaged global heap (the store of variable-length strings): every object in it claims 2^47 bytes.
// libhdf5 1.10 follows such a reference out of bounds; the validating walk of open_input meets it in a
// child process and refuses the file naming what it was reading, instead of the reader crashing.
TEST(Io, DamagedStringHeapIsRefusedNotFollowed) {
  const auto dir = temp_dir("heap");
  const auto path = (dir / "h.h5").string();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "mesh", test_run(), out.uuid());
    out.root().write_strings("names", {"alpha", "beta", "gamma"});
    out.commit();
  }
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // Collection: "GCOL", version, 3 reserved, size (8); then objects: index (2), references (2), reserved (4),
  // size (8), data padded to 8 bytes. Index 0 is the free space that ends the collection.
  int damaged = 0;
  for (std::size_t at = bytes.find("GCOL"); at != std::string::npos; at = bytes.find("GCOL", at + 4)) {
    std::uint64_t collection = 0;
    std::memcpy(&collection, bytes.data() + at + 8, 8);
    for (std::size_t obj = at + 16; obj + 16 <= std::min(bytes.size(), at + collection);) {
      std::uint16_t index = 0;
      std::uint64_t size = 0;
      std::memcpy(&index, bytes.data() + obj, 2);
      std::memcpy(&size, bytes.data() + obj + 8, 8);
      if (index == 0) break;
      const std::uint64_t huge = std::uint64_t{1} << 47;
      std::memcpy(bytes.data() + obj + 8, &huge, 8);
      ++damaged;
      obj += 16 + (size + 7) / 8 * 8;
    }
  }
  ASSERT_GT(damaged, 3) << "no string objects found in the file's global heap";
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  try {
    const io::Group root = io::open_input(path);
    FAIL() << "a file with a damaged string heap was opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damaged HDF5 file"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Mutants the fuzz found (tests/fuzz): a damaged integer type description of the root's format_version
// (libhdf5's integer conversion read out of bounds in about one run in twelve) and a damaged string heap
// under /provenance. Refused, naming the object, every time.
TEST(Io, FuzzFoundMutantsAreRefused) {
  const std::string dir = std::string(FRACTURE_TEST_DATA) + "/damaged/";
  for (int run = 0; run < 20; ++run) {
    try {
      const io::Group root = io::open_input(dir + "integer-type.h5");
      io::check_header(root, {"mesh"});
      FAIL() << "a damaged integer type was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("format_version"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(io::open_input(dir + "string-heap.h5"), InputError);
}
