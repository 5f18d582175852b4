#include "analysis/fragments_io.hpp"

#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/option_check.hpp"
#include "io/atomic_file.hpp"
#include "io/fragment_labels.hpp"
#include "io/mesh_io.hpp"
#include "io/series.hpp"

namespace frac::analysis {
// (The file formats are written with io's HDF5 and file layer throughout.)
using namespace frac::io;
namespace {

constexpr const char* kCells = "particles/cells";
constexpr const char* kBeams = "connectivity/beams";
constexpr const char* kBeamSeries = "connectivity/beams/trajectory";  // per-frame beam data (run_io)

void require_count(const Group& g, std::string_view name, std::size_t got, std::size_t want, const char* what) {
  if (got != want)
    throw InputError(g.where(name) + ": has " + std::to_string(got) + " values, expected " + std::to_string(want) +
                     " (" + what + ")");
}

template <class T>
std::vector<T> frame_of(const Group& parent, std::string_view name, std::int64_t frame, std::size_t want,
                        const char* what) {
  auto v = read_series_frame<T>(parent, name, frame);
  require_count(parent.group(name), "value", v.size(), want, what);
  return v;
}

// Frames as a run writes them: steps >= 0 and times finite and >= 0, neither decreasing (--time picks a frame
// by them, and the time series and the fragments file carry them).
void check_frame_list(const Group& cells, const RunInfo& info) {
  const Group series = cells.group("position");
  for (std::size_t k = 0; k < info.step.size(); ++k) {
    const std::string frame = ": frame " + std::to_string(k) + ": ";
    const double t = info.time[k];
    if (!(std::isfinite(t) && t >= 0 && (k == 0 || t >= info.time[k - 1])))
      throw InputError(series.where("time") + frame + "t = " + format_value(t) + " s" +
                       (k ? " after " + format_value(info.time[k - 1]) + " s" : "") +
                       " (frame times must be finite, >= 0 and non-decreasing)");
    if (!(info.step[k] >= 0 && (k == 0 || info.step[k] >= info.step[k - 1])))
      throw InputError(series.where("step") + frame + "step " + std::to_string(info.step[k]) +
                       (k ? " after " + std::to_string(info.step[k - 1]) : "") +
                       " (frame steps must be >= 0 and non-decreasing)");
  }
}

// A contiguous, uncompressed float64 dataset. Per-fragment columns are written this way: deflate
// gains little on their mantissas and costs about 0.4 s per 10^6 values, which would dominate a
// fragment count of a finely broken 10^6-cell run (docs/fragments.md).
void write_plain(Group& g, const char* name, std::span<const double> data, const std::vector<hsize_t>& dims,
                 std::string_view unit) {
  hsize_t count = 1;
  for (auto d : dims) count *= d;
  if (count != data.size())
    throw RuntimeError(g.where(name) + ": " + std::to_string(data.size()) + " values do not fill a dataset of " +
                       std::to_string(count));
  Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  Hid dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(dcpl.get(), 0);
  Hid d(H5Dcreate2(g.id(), name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (d.get() < 0)
    throw RuntimeError(g.where(name) + ": cannot create dataset (" + write_failure(g.file(), errno) + ")");
  if (count > 0 && H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw RuntimeError(g.where(name) + ": cannot write dataset (" + write_failure(g.file(), errno) + ")");
  g.set_attr("unit", unit, name);
}

}  // namespace

RunInfo read_dem_run_info(const Group& root) {
  if (root.has_attr("model") && root.attr_string("model") != "dem")
    throw InputError(root.file() + ": a run of model '" + root.attr_string("model") +
                     "'; fragments are counted in polygon-DEM runs (model 'dem')");
  RunInfo info = read_run_info(root);
  const Group cells = root.group(kCells);
  check_frame_list(cells, info);
  require_count(cells, "inertia", info.inertia.size(), info.mass.size(), "one per cell, as mass");
  const mesh::CellMesh mesh = read_cell_mesh(root);  // the run's mesh holds the invariants of mesh-gen check
  require_count(cells, "mass", info.mass.size(), mesh.cells(), "one per cell of the mesh");
  return info;
}

std::vector<std::int64_t> read_beam_pairs(const Group& root, std::size_t cells) {
  const Group beams = root.group(kBeams);
  auto pairs = beams.read<std::int64_t>("pairs", nullptr, 2, 2);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (pairs[k] < 0 || static_cast<std::size_t>(pairs[k]) >= cells)
      throw InputError(beams.where("pairs") + ": row " + std::to_string(k / 2) + " refers to cell " +
                       std::to_string(pairs[k]) + ", outside 0.." + std::to_string(static_cast<long long>(cells) - 1) +
                       " (the cells of /particles/cells/mass)");
  return pairs;
}

std::vector<std::uint8_t> read_beam_intact(const Group& root, std::int64_t frame, std::size_t beams) {
  const Group series = root.group(kBeamSeries);
  auto intact = frame_of<std::uint8_t>(series, "intact", frame, beams, "one per row of /connectivity/beams/pairs");
  // (any other value would count as intact and pass for a run's state)
  for (std::size_t k = 0; k < intact.size(); ++k)
    if (intact[k] > 1)
      throw InputError(series.where("intact/value") + ": frame " + std::to_string(frame) + ": beam " +
                       std::to_string(k) + ": intact flag " + std::to_string(intact[k]) + ", expected 0 or 1");
  return intact;
}

FragmentInput read_fragment_input(const Group& root, const RunInfo& info, std::int64_t frame) {
  const auto frames = static_cast<std::int64_t>(info.step.size());
  if (frame < 0 || frame >= frames)
    throw InputError(root.where(kCells) + ": no frame " + std::to_string(frame) + " (the run has " +
                     std::to_string(frames) + ")");
  FragmentInput in;
  in.frame = frame;
  in.step = info.step[static_cast<std::size_t>(frame)];
  in.time = info.time[static_cast<std::size_t>(frame)];
  in.mass = info.mass;
  in.inertia = info.inertia;
  const std::size_t n = in.mass.size();
  const Group cells = root.group(kCells);
  in.position = frame_of<double>(cells, "position", frame, 2 * n, "two per cell of /particles/cells/mass");
  in.velocity = frame_of<double>(cells, "velocity", frame, 2 * n, "two per cell of /particles/cells/mass");
  in.angular_velocity = frame_of<double>(cells, "angular_velocity", frame, n, "one per cell of /particles/cells/mass");
  in.beam = read_beam_pairs(root, n);
  in.intact = read_beam_intact(root, frame, in.beam.size() / 2);
  return in;
}

FragmentTimeSeries fragment_time_series(const Group& root, const RunInfo& info, std::span<const std::int64_t> beam,
                                        std::int64_t min_cells) {
  analysis::FragmentCounter counter;
  FragmentTimeSeries ts;
  for (std::size_t k = 0; k < info.step.size(); ++k) {
    const auto intact = read_beam_intact(root, static_cast<std::int64_t>(k), beam.size() / 2);
    const auto c = counter(info.mass, beam, intact, min_cells);
    ts.step.push_back(info.step[k]);
    ts.time.push_back(info.time[k]);
    ts.count.push_back(c.count);
    ts.largest_mass.push_back(c.largest_mass);
  }
  return ts;
}

void write_fragments(Group& root, const FragmentRecord& r) {
  const auto& f = r.fragments;
  const hsize_t n = f.cell_fragment.size(), nf = f.fragments();
  Group g = root.create_group("fragments");
  g.set_attr("frame", r.frame);
  g.set_attr("step", r.step);
  g.set_attr("time", r.time);
  g.set_attr("min_cells", r.min_cells);
  g.set_attr("total_mass", f.total_mass);
  g.set_attr("fragments", static_cast<std::int64_t>(nf));
  g.write("cell_fragment", std::span<const std::int64_t>(f.cell_fragment), {n});
  write_plain(g, "mass", f.mass, {nf}, "kg");
  g.write("cell_count", std::span<const std::int64_t>(f.cell_count), {nf});
  write_plain(g, "center_of_mass", f.center_of_mass, {nf, 2}, "m");
  write_plain(g, "velocity", f.velocity, {nf, 2}, "m s-1");
  write_plain(g, "kinetic_energy_translational", f.kinetic_energy_translational, {nf}, "J");
  write_plain(g, "kinetic_energy_rotational", f.kinetic_energy_rotational, {nf}, "J");

  const auto& h = r.histogram;
  const hsize_t k = h.count.size();
  if (h.edges.size() != (k ? k + 1 : 0) || h.density.size() != k)
    throw RuntimeError(g.where("histogram") + ": edges, counts and densities do not agree");
  std::vector<double> lower(h.edges.begin(), h.edges.begin() + static_cast<std::ptrdiff_t>(k));
  std::vector<double> upper(k ? h.edges.begin() + 1 : h.edges.end(), h.edges.end());
  Group hg = g.create_group("histogram");
  hg.set_attr("bins_per_decade", h.bins_per_decade);
  hg.set_attr("cell_mass", h.cluster_unit);
  hg.set_attr("min_cells", r.min_cells);
  hg.set_attr("n", h.n_total);
  hg.write("bin_lower", std::span<const double>(lower), {k}, "kg");
  hg.write("bin_upper", std::span<const double>(upper), {k}, "kg");
  hg.write("count", std::span<const std::int64_t>(h.count), {k}, "1");
  hg.write("density", std::span<const double>(h.density), {k}, "kg^-1");

  if (!r.time_series.empty()) {
    const auto& t = r.time_series;
    const hsize_t nt = t.step.size();
    Group tg = g.create_group("time_series");
    tg.set_attr("min_cells", r.min_cells);
    tg.write("step", std::span<const std::int64_t>(t.step), {nt});
    tg.write("time", std::span<const double>(t.time), {nt}, "s");
    tg.write("count", std::span<const std::int64_t>(t.count), {nt}, "1");
    tg.write("largest_mass", std::span<const double>(t.largest_mass), {nt}, "kg");
  }
}

FragmentRecord read_fragments(const Group& root) {
  FragmentRecord r;
  FragmentLabels labels = read_fragment_labels(root);
  const Group g = root.group("fragments");
  r.frame = labels.frame;
  r.step = labels.step;
  r.time = labels.time;
  r.min_cells = g.attr_int("min_cells");
  auto& f = r.fragments;
  f.total_mass = g.attr_double("total_mass");
  f.cell_fragment = std::move(labels.cell_fragment);
  f.mass = std::move(labels.mass);
  f.cell_count = std::move(labels.cell_count);
  const std::size_t nf = f.mass.size();
  f.center_of_mass = g.read<double>("center_of_mass", nullptr, 2, 2);
  require_count(g, "center_of_mass", f.center_of_mass.size(), 2 * nf, "two per fragment");
  f.velocity = g.read<double>("velocity", nullptr, 2, 2);
  require_count(g, "velocity", f.velocity.size(), 2 * nf, "two per fragment");
  f.kinetic_energy_translational = g.read<double>("kinetic_energy_translational", nullptr, 1);
  require_count(g, "kinetic_energy_translational", f.kinetic_energy_translational.size(), nf, "one per fragment");
  f.kinetic_energy_rotational = g.read<double>("kinetic_energy_rotational", nullptr, 1);
  require_count(g, "kinetic_energy_rotational", f.kinetic_energy_rotational.size(), nf, "one per fragment");
  // The smallest cell of each fragment, recomputed (the labels are checked).
  f.first_cell.assign(nf, -1);
  for (std::size_t i = f.cell_fragment.size(); i-- > 0;)
    f.first_cell[static_cast<std::size_t>(f.cell_fragment[i])] = static_cast<std::int64_t>(i);

  const Group h = g.group("histogram");
  auto& hist = r.histogram;
  hist.bins_per_decade = h.attr_double("bins_per_decade");
  if (h.has_attr("cell_mass")) hist.cluster_unit = h.attr_double("cell_mass");
  hist.n_total = h.attr_int("n");
  const auto lower = h.read<double>("bin_lower", nullptr, 1);
  const std::size_t k = lower.size();
  const auto upper = h.read<double>("bin_upper", nullptr, 1);
  require_count(h, "bin_upper", upper.size(), k, "one per bin, as bin_lower");
  for (std::size_t j = 0; j + 1 < k; ++j)
    if (upper[j] != lower[j + 1]) throw InputError(h.where("bin_upper") + ": bins do not follow each other");
  hist.count = h.read<std::int64_t>("count", nullptr, 1);
  require_count(h, "count", hist.count.size(), k, "one per bin, as bin_lower");
  hist.density = h.read<double>("density", nullptr, 1);
  require_count(h, "density", hist.density.size(), k, "one per bin, as bin_lower");
  hist.edges = lower;
  if (k) hist.edges.push_back(upper.back());
  for (std::size_t j = 0; j < k; ++j) {
    hist.width.push_back(upper[j] - lower[j]);
    hist.center.push_back(std::sqrt(upper[j] * lower[j]));
  }

  if (g.has("time_series")) {
    const Group t = g.group("time_series");
    auto& ts = r.time_series;
    ts.step = t.read<std::int64_t>("step", nullptr, 1);
    const std::size_t nt = ts.step.size();
    ts.time = t.read<double>("time", nullptr, 1);
    require_count(t, "time", ts.time.size(), nt, "one per step");
    ts.count = t.read<std::int64_t>("count", nullptr, 1);
    require_count(t, "count", ts.count.size(), nt, "one per step");
    ts.largest_mass = t.read<double>("largest_mass", nullptr, 1);
    require_count(t, "largest_mass", ts.largest_mass.size(), nt, "one per step");
  }
  return r;
}

}  // namespace frac::analysis
