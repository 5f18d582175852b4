#pragma once
// The speeds part of the file layout (docs/wave-speed.md, "File layout"): a file of kind "speeds" written
// by wave-speed holds, under /speeds, the measured fronts of a run (arrival time against distance and the
// fitted speed), the predicted continuum speeds, the lattice check and the comparison. Also the
// `--format text` rendering: one "key value" line per number.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/provenance.hpp"
#include "io/hdf5.hpp"

namespace frac::io {

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

struct MeasuredSpeed {
  std::string label;     // "longitudinal.x": mode and direction label, unique in the file
  std::string mode;      // longitudinal | shear
  double direction = 0;  // rad, lab, from +x
  bool ok = false;
  std::string failure;                               // why not ok
  double speed = kNoValue, speed_stderr = kNoValue;  // m/s, lab
  double intercept = kNoValue;                       // s: arrival = intercept + distance / speed
  double residual_rms = kNoValue;                    // s
  double frame_bound = kNoValue;  // m/s, worst-case error of whole-frame arrivals (see analysis/wave_speed.hpp)
  std::int64_t points = 0, rejected = 0;
  double range_min = 0, range_max = 0;  // m
  double predicted = kNoValue;          // m/s, lab prediction for this mode and direction (NaN: none)
  double deviation = kNoValue;          // speed / predicted - 1 (NaN: not compared)
  // The lattice's own long-wave speed at the run's cut-off when the run records it (rubber-run:
  // derived.lattice.*), and speed / that - 1. NaN: none.
  double lattice_predicted = kNoValue, lattice_deviation = kNoValue;
  // Per receiver bin: distance (m), arrival time (s, NaN: none), peak signal, used by the fit.
  std::vector<double> distance, arrival, amplitude;
  std::vector<std::uint8_t> used;
};

struct PredictedSpeed {
  std::string label;                                                     // direction label: x, y, -x, -y or "40deg"
  double direction = 0;                                                  // rad, lab
  double longitudinal = kNoValue, shear = kNoValue;                      // m/s, lab
  double longitudinal_reference = kNoValue, shear_reference = kNoValue;  // m/s, omega/|k_ref| (NaN: not defined)
};

struct NamedValue {
  std::string name;
  double value = kNoValue;
  std::string unit;
};

struct SpeedsRecord {
  std::string origin;  // "run" (measured, maybe compared) or "theory" (predicted only)

  // Measurement (origin "run").
  std::string model;      // rubber | dem
  std::string signal;     // displacement | velocity | strain
  std::string arrival;    // threshold | peak
  std::string amplitude;  // local | global | absolute
  double threshold = kNoValue;
  std::array<double, 2> source{kNoValue, kNoValue};  // m, lab
  std::string source_from;                           // option | parameters | frames
  double frame_interval = kNoValue;                  // s
  std::int64_t frames = 0;
  double bin = kNoValue;                          // m
  std::array<double, 4> deformation{1, 0, 0, 1};  // F of the first frame, row-major
  std::vector<MeasuredSpeed> measured;

  // Prediction.
  std::string theory;                  // "" (none) | mooney-rivlin | plane-stress
  std::string formulas;                // the formulas used, as text
  std::vector<NamedValue> parameters;  // a, b, density, stretch_x, stretch_y | young, poisson, density
  std::vector<PredictedSpeed> predicted;
  std::vector<NamedValue> stress;  // Mooney-Rivlin: piola_xx, piola_yy, cauchy_xx, cauchy_yy (N/m)

  // Lattice check (rubber).
  std::string lattice_regime;  // "" (not checked) | mooney-rivlin | short-bonds | near-cutoff | broken | unchecked
  std::string lattice_message;
  std::vector<double> bond_angle, bond_length;  // rad (reference direction), m (at the stretch)

  std::string comparison;  // "compared", or why not ("not compared: ...")
};

// Writes /speeds under root (the header is the caller's, kind "speeds").
void write_speeds(Group& root, const SpeedsRecord& r);
// InputError naming the dataset when /speeds is missing or malformed.
SpeedsRecord read_speeds(const Group& root);
// "key value" lines (values to 10 significant digits, text values verbatim), for --format text, after
// `provenance` (frac::provenance_line) as a '#' line.
std::string speeds_text(const SpeedsRecord& r, const std::string& provenance);
// Writes `path` ("-": standard output) whole: the key value lines of speeds_text (text) or an HDF5 file of
// kind "speeds" (header and /speeds) for `run`.
void write_speeds_file(const std::string& path, const SpeedsRecord& r, const ToolRun& run, bool text);

}  // namespace frac::io
