#pragma once
// Wave speeds measured from a run's frames (either model: rubber nodes or DEM cells, io/run_io.hpp).
//
// Receivers: every body (or, for the strain signal, every link at its midpoint), placed by its position
// in the first frame (the lab frame of the sheet at rest, pre-stretch included). For a propagation
// direction n from the source x0, a receiver sits at distance s = (p - x0)·n and lateral offset
// l = (p - x0)·n_perp; receivers are binned by |s| (or by s on one side) in bins of about a lattice
// spacing. For a point source (the DEM pulse scene) the direction may be radial: s = |p - x0| and n is
// the receiver's own unit vector (p - x0)/|p - x0|. The signal of a bin in a frame is the RMS over its
// receivers of
//   displacement: (x(t) - x(t0))·n (longitudinal) or ·n_perp (shear), t0 = the first frame;
//   velocity:     v(t)·n or v(t)·n_perp;
//   strain:       link strain change eps(t) - eps(t0) (blind to polarisation: the mode is a label).
// Arrival: the first time the bin's signal reaches `threshold` × the pulse amplitude (the bin's own
// peak by default: insensitive to geometric spreading and to the pulse splitting in two), linearly
// interpolated between the two frames that bracket the crossing. A straight line t = t0 + s/c fitted to
// the arrivals (least squares, with robust rejection of outliers such as bins reached first by a
// reflection) gives the lab speed c and its standard error.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "io/hdf5.hpp"

namespace frac::analysis {

enum class WaveMode { longitudinal, shear };
enum class Signal { displacement, velocity, strain };
enum class AmplitudeRef { local, global, absolute };
enum class Side { both, forward, backward };
// What marks the arrival at a distance: the first time the signal reaches the threshold (the front), or
// the first peak after that (the pulse's maximum). In a dispersive lattice both run ahead of the long-wave
// speed by O(1/width^2) (docs/wave-speed.md §2.4); the peak is an independent check.
enum class Arrival { threshold, peak };

std::string_view name(WaveMode m);
std::string_view name(Signal s);
std::string_view name(AmplitudeRef a);
std::string_view name(Side s);
std::string_view name(Arrival a);
// Parsers: UsageError naming `option` for an unknown word.
WaveMode parse_wave_mode(std::string_view text, std::string_view option);
Signal parse_signal(std::string_view text, std::string_view option);
Side parse_side(std::string_view text, std::string_view option);
Arrival parse_arrival(std::string_view text, std::string_view option);

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The direction value that stands for "radial, from the source" (a NaN).
inline constexpr double kRadial = std::numeric_limits<double>::quiet_NaN();
inline bool is_radial(double direction) { return std::isnan(direction); }

struct FrontOptions {
  std::vector<double> directions{0.0};  // rad, lab propagation directions from +x; kRadial: radial
  // Modes to measure; empty: each mode whose strongest signal reaches `auto_mode_fraction` of the
  // strongest of the two (a longitudinal pulse has no shear component to measure, and vice versa).
  std::vector<WaveMode> modes;
  double auto_mode_fraction = 0.1;
  Signal signal = Signal::displacement;
  std::optional<Eigen::Vector2d> source;  // m, lab; empty: source_reference, else inferred from the frames
  // m, a point of the reference (unstretched) mesh, mapped to the lab by the first frame's fitted affine
  // deformation (used when `source` is empty): how a scene that places its pulse in the mesh says where.
  std::optional<Eigen::Vector2d> source_reference;
  // m, reference length: the automatic range starts at least this far from the source (times the stretch
  // along the direction), e.g. 3 widths of the initial pulse, which sits in the first frame.
  double near_field = 0;
  double threshold = 0.5;  // fraction of the amplitude that marks the arrival, in (0, 1)
  AmplitudeRef amplitude = AmplitudeRef::local;
  double amplitude_value = 0;  // the amplitude, for AmplitudeRef::absolute (m, m/s or 1 by signal)
  double floor = 1e-3;         // bins whose peak is below floor × the strongest bin's have no arrival
  double bin = 0;              // m, bin width along n; 0: the median link length in the first frame
  double lateral = 0;          // m, half-width of the band |l| <= lateral around the ray; 0: no limit
  // m, fitted distance range; NaN: max(0.25 of the farthest receiver, near_field) and 0.95 of it
  double s_min = kNaN, s_max = kNaN;
  double t_min = -std::numeric_limits<double>::infinity();  // s, frames used
  double t_max = std::numeric_limits<double>::infinity();
  Side side = Side::both;
  double reject = 4.0;      // drop arrivals further than reject × robust sigma from the line; 0: keep all
  bool interpolate = true;  // sub-frame arrival times (else: the first frame at or above the level)
  Arrival arrival = Arrival::threshold;
};

// An --amplitude value: local, global or a number (absolute): sets front.amplitude and amplitude_value.
// UsageError naming `option` for anything else.
void parse_amplitude(std::string_view text, std::string_view option, FrontOptions& front);

// Least-squares line y = intercept + slope·x through the points with used[k] = 1, with standard errors
// from the residuals (n - 2 degrees of freedom).
struct LineFit {
  double slope = kNaN, intercept = kNaN;
  double slope_stderr = kNaN, intercept_stderr = kNaN;
  double residual_rms = kNaN;
  std::size_t points = 0, rejected = 0;
};
// Robust straight-line fit: least squares, then repeatedly drop (or readmit) points whose residual exceeds
// max(reject × 1.4826 × MAD of the residuals, min_tolerance), until the set is stable. reject = 0 keeps
// every point. Non-finite y are never used. `used` (resized to x.size()) says which points were used.
// RuntimeError-free: a fit with fewer than 3 points returns points < 3 and NaN values.
LineFit fit_line(std::span<const double> x, std::span<const double> y, double reject, double min_tolerance,
                 std::vector<std::uint8_t>& used);

// First time a signal reaches `level`: NaN when it never does in the series or already does at its first
// entry (the front was there before the first frame). With `interpolate`, linear between the bracketing
// entries.
double first_crossing(std::span<const double> time, std::span<const double> signal, double level, bool interpolate);
// Time of the first local maximum at or after the first crossing of `level` (NaN when there is no
// crossing or the maximum is the last entry): the vertex of the parabola through the maximum and its two
// neighbours with `interpolate`, else the frame of the maximum.
double first_peak(std::span<const double> time, std::span<const double> signal, double level, bool interpolate);

struct FrontMeasurement {
  WaveMode mode = WaveMode::longitudinal;
  double direction = 0;  // rad, or kRadial
  bool ok = false;
  std::string failure;          // why not ok
  double s_min = 0, s_max = 0;  // m, distance range used
  // One entry per receiver bin in the range: mean distance (m), arrival time (s; NaN: none), the bin's
  // peak signal, and whether the fit used it.
  std::vector<double> distance, arrival, amplitude;
  std::vector<std::uint8_t> used;
  double peak = 0;             // strongest bin signal
  double level = kNaN;         // arrival level when it is one number (global or absolute amplitude)
  LineFit fit;                 // arrival = intercept + slope · distance
  double speed = kNaN;         // m/s, lab, = 1/slope
  double speed_stderr = kNaN;  // m/s, standard error of the fit, = slope_stderr / slope^2
  // Worst-case speed error if every arrival were rounded up to the next frame (no interpolation):
  // 1.5 · frame_interval · c^2 / (span of the fitted distances). A scale for the frame spacing's effect.
  double frame_bound = kNaN;
};

struct WaveMeasurement {
  Eigen::Vector2d source{0, 0};  // m, lab
  // "option", "reference" (source_reference mapped to the lab) or "frames" (velocity-weighted centroid of
  // the first frame in which something moves)
  std::string source_from;
  Signal signal = Signal::displacement;
  double frame_interval = 0;  // s, median spacing of the frames used
  std::size_t frames = 0;     // frames used
  double bin = 0;             // m
  std::string model;          // "rubber" or "dem"
  // Homogeneous deformation of the first frame against the mesh's reference positions, least squares over
  // the intact links: p_j - p_i = F (r_j - r_i). For the rubber lattice, diag(lambda_x, lambda_y) when the
  // sheet starts homogeneously pre-stretched.
  Eigen::Matrix2d deformation = Eigen::Matrix2d::Identity();
  std::vector<FrontMeasurement> fronts;
};

// Measures the fronts of a run file (kind "run"). UsageError for bad options; InputError when the run has
// fewer than 3 frames in the window or nothing moves. A front that cannot be timed (too few arrivals,
// times that do not grow with distance) comes back with ok = false and its `failure`; with automatic
// modes, only the modes present in the signal come back.
WaveMeasurement measure_wave_speeds(const io::Group& run, const FrontOptions& opt);

}  // namespace frac::analysis
