// Checkpoints: the state archive's round trip through a file, what it refuses (a damaged state, an entry of
// another size or type, a value out of range), the run identity, and the integrator continued from its state.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/checkpoint_options.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "dynamics/integrator.hpp"
#include "io/checkpoint.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"
#include "mesh/node_mesh.hpp"
#include "mesh_test_support.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace frac;
using frac::test::temp_dir;

namespace {

struct Record {
  std::int32_t index;
  bool flag;
  double value;
};

// Everything an object might hold, named once for saving and loading.
struct Holder {
  std::vector<double> x;
  std::vector<std::int64_t> n;
  std::vector<std::uint8_t> bytes;
  std::vector<std::size_t> sizes;
  std::vector<Record> records;
  long long steps = 0;
  bool on = false;
  double t = 0;
  void visit(StateArchive& a) {
    StateArchive::Scope scope(a, "holder");
    a.array("x", x, x.size());
    a.array("n", n);
    a.array("bytes", bytes);
    a.array("sizes", sizes);
    a.value("steps", steps);
    a.value("on", on);
    a.value("t", t);
    std::size_t count = records.size();
    a.value("records", count);
    if (a.loading()) records.resize(count);
    a.field("index", records, &Record::index);
    a.field("flag", records, &Record::flag);
    a.field("value", records, &Record::value);
  }
};

void save(const std::string& path, Holder& h) {
  io::OutputFile out(path);
  io::StateWriter w(out.root().create_group("state"));
  h.visit(w);
  w.finish();
  out.commit();
}

// Flips one byte of the file at the first occurrence of `needle` (a value's bytes).
void flip_bytes_of(const std::string& path, const std::string& needle) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto at = data.find(needle);
  ASSERT_NE(at, std::string::npos);
  f.seekp(static_cast<std::streamoff>(at));
  f.put(static_cast<char>(data[at] ^ 0x10));
}

}  // namespace

TEST(Checkpoint, StateRoundTripIsExact) {
  const auto path = (temp_dir("round") / "s.h5").string();
  Holder h;
  h.x = {1.0 / 3.0, -0.0, 1e-300, std::nextafter(1.0, 2.0)};
  h.n = {-5, 1LL << 60};
  h.bytes = {0, 255, 7};
  h.sizes = {3, 0, 12345678901ULL};
  h.records = {{7, true, 0.1}, {-2, false, -1e20}};
  h.steps = 123456789012LL;
  h.on = true;
  h.t = 2.5e-3;
  save(path, h);
  Holder back;
  back.x.assign(4, 0.0);
  const io::Group root = io::open_input(path);
  io::StateReader r(root.group("state"));
  back.visit(r);
  EXPECT_EQ(back.x, h.x);
  EXPECT_TRUE(std::signbit(back.x[1]));
  EXPECT_EQ(back.n, h.n);
  EXPECT_EQ(back.bytes, h.bytes);
  EXPECT_EQ(back.sizes, h.sizes);
  EXPECT_EQ(back.steps, h.steps);
  EXPECT_TRUE(back.on);
  EXPECT_EQ(back.t, h.t);
  ASSERT_EQ(back.records.size(), 2u);
  EXPECT_EQ(back.records[1].index, -2);
  EXPECT_FALSE(back.records[1].flag);
  EXPECT_EQ(back.records[1].value, -1e20);
}

TEST(Checkpoint, RefusesAnEntryOfAnotherSizeOrType) {
  const auto path = (temp_dir("size") / "s.h5").string();
  Holder h;
  h.x = {1, 2, 3};
  save(path, h);
  const io::Group root = io::open_input(path);
  {
    Holder back;
    back.x.assign(4, 0.0);  // the run needs 4 values
    io::StateReader r(root.group("state"));
    try {
      back.visit(r);
      FAIL() << "an entry of another size was loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("holder/x: holds 3 values, the run needs 4"), std::string::npos) << e.what();
    }
  }
  io::StateReader r(root.group("state"));
  std::vector<double> as_double;
  StateArchive::Scope scope(r, "holder");
  EXPECT_THROW(r.array("n", as_double), InputError);  // int64, not float64
  std::vector<std::uint8_t> missing;
  EXPECT_THROW(r.array("no_such_entry", missing), InputError);  // missing
}

TEST(Checkpoint, RefusesValuesOutOfRange) {
  const auto path = (temp_dir("range") / "s.h5").string();
  Holder h;
  h.n = {-1, 300};
  save(path, h);
  const io::Group root = io::open_input(path);
  io::StateReader r(root.group("state"));
  StateArchive::Scope scope(r, "holder");
  std::vector<std::uint16_t> narrow;
  EXPECT_THROW(r.array("n", narrow), InputError);  // -1 does not fit an unsigned type
  std::vector<std::int64_t> wide;
  r.array("n", wide);
  EXPECT_THROW(r.require_below("n", wide, 10), InputError);
}

TEST(Checkpoint, ADamagedStateFailsItsChecksum) {
  const auto path = (temp_dir("damaged") / "s.h5").string();
  Holder h;
  // A value whose bytes are easy to find in the file (stored uncompressed: a small dataset).
  h.x = {1.2345678901234567e+100};
  save(path, h);
  double v = h.x[0];
  flip_bytes_of(path, std::string(reinterpret_cast<const char*>(&v), sizeof v));
  const io::Group root = io::open_input(path);
  try {
    io::StateReader r(root.group("state"));
    FAIL() << "a damaged state was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
  }
}

TEST(Checkpoint, RunKeyNamesWhatMustMatch) {
  ToolRun a = start_run("dem-run", "dem-run x");
  a.parameters = {{"material.t_eps", "0.03"}, {"scene", "a/explosion.ini"}};
  a.seed = "1";
  a.input_uuids = {"u1"};
  ToolRun b = a;
  b.parameters[1].second = "elsewhere/explosion.ini";  // the scene's path: not part of the run
  b.command_line = "dem-run --threads 2 x";            // nor the command line
  EXPECT_EQ(io::run_key(a), io::run_key(b));
  b.parameters[0].second = "0.05";
  EXPECT_NE(io::run_key(a), io::run_key(b));
  ToolRun c = a;
  c.seed = "2";
  EXPECT_NE(io::run_key(a), io::run_key(c));
  ToolRun d = a;
  d.input_uuids = {"u2"};
  EXPECT_NE(io::run_key(a), io::run_key(d));
}

TEST(Checkpoint, CheckpointEveryTakesStepsOrWallTime) {
  CheckpointOptions o;
  parse_checkpoint_every("2500", "--checkpoint-every", o);
  EXPECT_EQ(o.every_steps, 2500);
  EXPECT_EQ(o.every_seconds, 0);
  parse_checkpoint_every("15min", "--checkpoint-every", o);
  EXPECT_EQ(o.every_steps, 0);
  EXPECT_EQ(o.every_seconds, 900);
  parse_checkpoint_every("1.5h", "--checkpoint-every", o);
  EXPECT_EQ(o.every_seconds, 5400);
  parse_checkpoint_every("0", "--checkpoint-every", o);
  EXPECT_FALSE(o.periodic());
  for (const char* bad : {"", "-5", "10x", "1.5", "nan", "5 min", "1e400s", "min"})
    EXPECT_THROW(parse_checkpoint_every(bad, "--checkpoint-every", o), UsageError) << bad;
  EXPECT_EQ(checkpoint_path(o, "run.h5"), "run.h5.ckpt");
  EXPECT_EQ(checkpoint_path(o, "-"), "");
  o.path = "x.ckpt";
  EXPECT_EQ(checkpoint_path(o, "-"), "x.ckpt");
}

// A harmonic oscillator stepped 200 times equals one stepped 80 times, saved, loaded into a fresh integrator
// started elsewhere, and stepped 120 more: both schemes, to the bit.
TEST(Checkpoint, IntegratorContinuesBitForBit) {
  struct Oscillator : dynamics::System {
    void accelerations(double, std::span<const double> q, std::span<const double> v, std::span<double> a) override {
      for (std::size_t i = 0; i < q.size(); ++i) a[i] = -4.0 * q[i] - 0.1 * v[i];
    }
  } osc;
  const auto dir = temp_dir("integrator");
  for (auto kind : {dynamics::IntegratorKind::gear5, dynamics::IntegratorKind::verlet}) {
    const std::vector<double> q0{1.0, -0.5, 0.25}, v0{0.0, 0.3, -0.2};
    auto whole = dynamics::make_integrator(kind);
    whole->start(osc, 0.0, 0.01, q0, v0);
    for (int k = 0; k < 200; ++k) whole->step(osc);

    auto first = dynamics::make_integrator(kind);
    first->start(osc, 0.0, 0.01, q0, v0);
    for (int k = 0; k < 80; ++k) first->step(osc);
    const auto path = (dir / ("s" + std::string(dynamics::name(kind)) + ".h5")).string();
    {
      io::OutputFile out(path);
      io::StateWriter w(out.root().create_group("state"));
      first->visit_state(w);
      w.finish();
      out.commit();
    }
    auto second = dynamics::make_integrator(kind);
    second->start(osc, 0.0, 0.01, std::vector<double>{9, 9, 9}, std::vector<double>{9, 9, 9});
    const io::Group root = io::open_input(path);
    io::StateReader r(root.group("state"));
    second->visit_state(r);
    for (int k = 0; k < 120; ++k) second->step(osc);
    EXPECT_EQ(second->steps(), whole->steps());
    EXPECT_EQ(second->t(), whole->t());
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(second->q()[i], whole->q()[i]) << dynamics::name(kind);
      EXPECT_EQ(second->v()[i], whole->v()[i]) << dynamics::name(kind);
    }
  }
}

// The output so far, copied into a checkpoint and replayed into a new run file: the frames, observables and break
// events come back as written; a value damaged in the copy is refused by the series' checksum.
TEST(Checkpoint, OutputSoFarReplaysAndDamageIsRefused) {
  const auto dir = temp_dir("replay");
  const mesh::NodeMesh m = test::two_node_mesh();
  const std::vector<double> mass{1.0, 1.0};
  const auto copy_path = (dir / "copy.h5").string();
  {
    io::OutputFile out((dir / "run.h5").string());
    io::RunWriter w(out.root(), m, mass);
    io::BodyFrame f;
    f.position = {0, 0, 1, 0};
    f.velocity = {0, 0, 0, 0};
    f.intact = {1};
    f.strain = {0.0};
    for (int k = 0; k < 5; ++k) {
      f.step = k;
      f.time = 0.1 * k;
      f.position[2] = 1 + 0.01 * k;
      w.write_frame(f);
      w.observe("energy", k, 0.1 * k, 1.5 * k, "J");
    }
    w.record_break({3, 0.3, 0, 1});
    io::OutputFile copy(copy_path);
    io::Group run = copy.root().create_group("run");
    w.copy_progress(run);
    copy.commit();
  }
  {
    io::OutputFile out((dir / "continued.h5").string());
    io::RunWriter w(out.root(), m, mass);
    const io::Group copy = io::open_input(copy_path);
    w.replay(copy.group("run"));
    EXPECT_EQ(w.frames(), 5u);
    w.finish();
    out.commit();
  }
  const io::Group continued = io::open_input((dir / "continued.h5").string());
  EXPECT_EQ(io::read_frame(continued, -1).position[2], 1.04);
  EXPECT_EQ(io::read_breaks(continued).size(), 1u);
  EXPECT_EQ(continued.group("observables/energy").read<double>("value").back(), 6.0);

  // One value of the copy changed: refused, naming the series.
  {
    io::Hid file(H5Fopen(copy_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    io::Hid d(H5Dopen2(file.get(), "/run/observables/energy/value", H5P_DEFAULT));
    io::Hid space(H5Dget_space(d.get()));
    const hsize_t start = 2, count = 1;
    H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    io::Hid mem(H5Screate_simple(1, &count, nullptr));
    const double damaged = 3.25;
    ASSERT_GE(H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT, &damaged), 0);
  }
  io::OutputFile out((dir / "refused.h5").string());
  io::RunWriter w(out.root(), m, mass);
  const io::Group copy = io::open_input(copy_path);
  try {
    w.replay(copy.group("run"));
    FAIL() << "a damaged copy was replayed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/run/observables/energy: damaged"), std::string::npos) << e.what();
  }
}
