#pragma once
// The fragments part of the file layout (docs/fragments.md): what fragment-count reads from a run
// file (one frame of a DEM run, without the polygons) and the /fragments group it writes, read back
// here too. Every reader checks shapes and names the file and dataset at fault (InputError).
//
//   /fragments   attrs frame, step, time (s), min_cells, total_mass (kg), fragments (F)
//     cell_fragment [N] int64, mass [F] kg, cell_count [F] int64, center_of_mass [F,2] m,
//     velocity [F,2] m s-1, kinetic_energy_translational [F] J, kinetic_energy_rotational [F] J
//   /fragments/histogram    attrs bins_per_decade, min_cells, n (masses binned);
//                           bin_lower [K] kg, bin_upper [K] kg, count [K] int64, density [K] kg^-1
//   /fragments/time_series  step [T] int64, time [T] s, count [T] int64, largest_mass [T] kg  (optional)
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/fragments.hpp"
#include "io/hdf5.hpp"
#include "io/run_io.hpp"

namespace frac::analysis {

// One frame of a DEM run with what fragment counting needs: static masses and inertias, the beam
// pairs, and the frame's centroids, velocities, angular velocities and intact flags.
struct FragmentInput {
  std::int64_t frame = 0;  // index into the run's frames, >= 0
  std::int64_t step = 0;
  double time = 0.0;
  std::vector<double> mass, inertia, position, velocity, angular_velocity;
  std::vector<std::int64_t> beam;  // [2B]
  std::vector<std::uint8_t> intact;
  CellState state() const { return {mass, inertia, position, velocity, angular_velocity, beam, intact}; }
};

// The run's static data and frame list; InputError unless `root` is a DEM run (model "dem") whose
// mass and inertia agree in length and whose frames have steps >= 0 and finite times >= 0, neither decreasing.
io::RunInfo read_dem_run_info(const io::Group& root);
// /connectivity/beams/pairs as [2B], checked to name cells 0..cells-1.
std::vector<std::int64_t> read_beam_pairs(const io::Group& root, std::size_t cells);
// Frame `frame` (0 <= frame < frames) of /connectivity/beams/trajectory/intact, checked to hold `beams` flags,
// each 0 or 1.
std::vector<std::uint8_t> read_beam_intact(const io::Group& root, std::int64_t frame, std::size_t beams);
// Everything for frame `frame` (0 <= frame < info.step.size()), sizes checked against the masses.
FragmentInput read_fragment_input(const io::Group& root, const io::RunInfo& info, std::int64_t frame);

struct FragmentTimeSeries {
  std::vector<std::int64_t> step;
  std::vector<double> time;
  std::vector<std::int64_t> count;  // fragments of at least min_cells cells
  std::vector<double> largest_mass;
  bool empty() const { return step.empty(); }
};

// The fragment count and largest fragment mass of every frame of the run (only the intact flags
// of each frame are read); `beam` as from read_beam_pairs.
FragmentTimeSeries fragment_time_series(const io::Group& root, const io::RunInfo& info,
                                        std::span<const std::int64_t> beam, std::int64_t min_cells);

struct FragmentRecord {
  std::int64_t frame = 0, step = 0;
  double time = 0.0;
  std::int64_t min_cells = 1;
  Fragments fragments;             // first_cell is not stored (recomputed on reading)
  LogHistogram histogram;          // of the masses of the fragments of at least min_cells cells
  FragmentTimeSeries time_series;  // written only when not empty
};

// Writes /fragments (the header is the caller's: kind "fragments").
void write_fragments(io::Group& root, const FragmentRecord& r);
// Reads /fragments back; InputError naming the dataset when shapes disagree.
FragmentRecord read_fragments(const io::Group& root);

}  // namespace frac::analysis
