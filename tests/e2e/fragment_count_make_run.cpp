// Test and benchmark helper for fragment-count (not a tool): turns a cell mesh into a small DEM run
// file without running dynamics, with beams broken by rule so the fragments are known.
//   fragment_count_make_run MESH|- OUT [--frames T] [--break-fraction P] [--cut-x X] [--seed S]
//                           [--corrupt inertia|pairs|intact]
// Frame k of T (k = 0..T-1) is at step 100 k, time 1e-3 k s. A beam is broken in frame k when its
// random draw u (uniform, per beam) is below P k/(T-1), and, from frame 1 on, when its two cells lie
// on either side of the line x = X (by reference centroid). Masses and inertias: density 2500 kg/m^3,
// thickness 0.01 m. Cells move by a uniform expansion about the origin plus a rigid rotation, with a
// random spin each. --corrupt writes a run that fragment-count must refuse: inertia one value short,
// a beam naming a cell past the last, or intact flags one short per frame.
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/provenance.hpp"
#include "core/rng.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"

using namespace frac;

namespace {

void replace(io::Group& g, const char* name) {
  if (H5Ldelete(g.id(), name, H5P_DEFAULT) < 0) throw RuntimeError(g.where(name) + ": cannot delete");
}

int make(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: fragment_count_make_run MESH|- OUT [--frames T] [--break-fraction P] [--cut-x X] "
                 "[--seed S] [--corrupt inertia|pairs|intact]\n";
    return 2;
  }
  const std::string mesh_path = argv[1], out_path = argv[2];
  long frames = 3;
  double fraction = 0.0, cut_x = HUGE_VAL;
  std::uint64_t seed = 1;
  std::string corrupt;
  for (int k = 3; k + 1 < argc; k += 2) {
    const std::string key = argv[k], value = argv[k + 1];
    if (key == "--frames")
      frames = std::stol(value);
    else if (key == "--break-fraction")
      fraction = std::stod(value);
    else if (key == "--cut-x")
      cut_x = std::stod(value);
    else if (key == "--seed")
      seed = std::stoull(value);
    else if (key == "--corrupt")
      corrupt = value;
    else
      throw UsageError("unknown option " + key);
  }
  if (frames < 1) throw UsageError("--frames: at least 1");

  const io::Group in = io::open_input(mesh_path);
  io::check_header(in, {"mesh", "run"});
  const mesh::CellMesh m = io::read_cell_mesh(in);
  const std::size_t n = m.cells(), b = m.beams();
  const double rho_h = 2500.0 * 0.01;
  std::vector<double> mass(n), inertia(n);
  for (std::size_t k = 0; k < n; ++k) {
    mass[k] = rho_h * m.area[k];
    inertia[k] = rho_h * m.second_moment[k];
  }
  Rng rng(seed);
  std::vector<double> draw(b), spin(n);
  for (auto& u : draw) u = rng.uniform();
  for (auto& w : spin) w = rng.uniform(-10.0, 10.0);

  ToolRun run = start_run("fragment_count_make_run", "fragment_count_make_run " + mesh_path + " " + out_path);
  io::add_input(run, in);
  io::OutputFile out(out_path);
  io::write_header(out.root(), "run", run, out.uuid());
  {
    io::RunWriter writer(out.root(), m, mass, inertia);
    io::BodyFrame f;
    f.position.resize(2 * n);
    f.velocity.resize(2 * n);
    f.angle.assign(n, 0.0);
    f.angular_velocity = spin;
    f.intact.resize(b);
    f.strain.assign(b, 0.0);
    for (long k = 0; k < frames; ++k) {
      f.step = 100 * k;
      f.time = 1e-3 * static_cast<double>(k);
      const double p = frames > 1 ? fraction * static_cast<double>(k) / static_cast<double>(frames - 1) : fraction;
      for (std::size_t j = 0; j < b; ++j) {
        const double xa = m.centroid[m.beam[j][0]].x(), xb = m.centroid[m.beam[j][1]].x();
        const bool cut = k > 0 && ((xa < cut_x) != (xb < cut_x));
        f.intact[j] = (draw[j] < p || cut) ? 0 : 1;
      }
      const double grow = 1.0 + 0.1 * f.time;
      for (std::size_t i = 0; i < n; ++i) {
        const double x = m.centroid[i].x(), y = m.centroid[i].y();
        f.position[2 * i] = grow * x;
        f.position[2 * i + 1] = grow * y;
        f.velocity[2 * i] = 0.1 * x - 2.0 * y + 0.5;
        f.velocity[2 * i + 1] = 0.1 * y + 2.0 * x - 0.25;
      }
      writer.write_frame(f);
    }
    writer.finish();
  }
  io::Group& root = out.root();
  if (corrupt == "inertia") {
    io::Group cells = root.group("particles/cells");
    replace(cells, "inertia");
    cells.write("inertia", std::span<const double>(inertia.data(), n - 1), {n - 1}, "kg m^2");
  } else if (corrupt == "pairs") {
    io::Group beams = root.group("connectivity/beams");
    std::vector<std::int64_t> pairs;
    for (const auto& p : m.beam) pairs.insert(pairs.end(), p.begin(), p.end());
    pairs.back() = static_cast<std::int64_t>(n);
    replace(beams, "pairs");
    beams.write("pairs", std::span<const std::int64_t>(pairs), {b, 2});
  } else if (corrupt == "intact") {
    io::Group intact = root.group("connectivity/beams/trajectory/intact");
    replace(intact, "value");
    std::vector<std::uint8_t> flags(static_cast<std::size_t>(frames) * (b - 1), 1);
    intact.write("value", std::span<const std::uint8_t>(flags), {static_cast<hsize_t>(frames), b - 1});
  } else if (!corrupt.empty()) {
    throw UsageError("--corrupt: inertia, pairs or intact");
  }
  out.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  io::silence_hdf5_errors();
  try {
    return make(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "fragment_count_make_run: error: " << e.what() << "\n";
    return 2;
  }
}
