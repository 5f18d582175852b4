#include "analysis/wave_speed.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <sstream>

#include <Eigen/Dense>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/mesh_io.hpp"
#include "io/run_io.hpp"
#include "io/series.hpp"

namespace frac::analysis {
namespace {

using Vec2 = Eigen::Vector2d;

std::string number(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  double m = *mid;
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
  return m;
}

// Plain least squares through the used points.
LineFit least_squares(std::span<const double> x, std::span<const double> y, const std::vector<std::uint8_t>& used) {
  LineFit f;
  double n = 0, sx = 0, sy = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (used[k]) n += 1, sx += x[k], sy += y[k];
  f.points = static_cast<std::size_t>(n);
  if (f.points < 3) return f;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (used[k]) sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
  if (!(sxx > 0)) return f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double ss = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (used[k]) {
      const double r = y[k] - f.intercept - f.slope * x[k];
      ss += r * r;
    }
  const double s2 = ss / (n - 2);
  f.residual_rms = std::sqrt(ss / n);
  f.slope_stderr = std::sqrt(s2 / sxx);
  f.intercept_stderr = std::sqrt(s2 * (1 / n + mx * mx / sxx));
  return f;
}

// A polarisation whose strongest signal is below this fraction of the other's is round-off, not a wave.
constexpr double kNoiseFraction = 1e-6;

struct Receiver {
  std::size_t index;  // body, or link for the strain signal
  std::size_t bin;
};

// One front being measured: its receivers' bins and the per-frame signal of every bin.
struct Track {
  double direction;
  WaveMode mode;
  Vec2 n;  // the unit vector the signal is projected on (n, or n_perp for shear)
  bool radial = false;
  std::vector<Vec2> unit;  // radial: each receiver's unit vector from the source (n_perp for shear)
  double s_min, s_max;
  std::vector<double> bin_distance;  // mean |s| of each bin's receivers
  std::vector<std::size_t> bin_count;
  std::vector<Receiver> receivers;
  std::vector<std::vector<double>> signal;  // [bin][frame]
};

}  // namespace

std::string_view name(WaveMode m) { return m == WaveMode::longitudinal ? "longitudinal" : "shear"; }
std::string_view name(Signal s) {
  return s == Signal::displacement ? "displacement" : s == Signal::velocity ? "velocity" : "strain";
}
std::string_view name(AmplitudeRef a) {
  return a == AmplitudeRef::local ? "local" : a == AmplitudeRef::global ? "global" : "absolute";
}
std::string_view name(Arrival a) { return a == Arrival::threshold ? "threshold" : "peak"; }
Arrival parse_arrival(std::string_view text, std::string_view option) {
  if (text == "threshold") return Arrival::threshold;
  if (text == "peak") return Arrival::peak;
  throw UsageError(std::string(option) + ": expected threshold or peak, got '" + std::string(text) + "'");
}
std::string_view name(Side s) { return s == Side::both ? "both" : s == Side::forward ? "forward" : "backward"; }

void parse_amplitude(std::string_view text, std::string_view option, FrontOptions& front) {
  if (text == "local" || text == "global") {
    front.amplitude = text == "local" ? AmplitudeRef::local : AmplitudeRef::global;
    return;
  }
  const std::string value(text);
  try {
    std::size_t used = 0;
    front.amplitude_value = std::stod(value, &used);
    if (used != value.size()) throw std::invalid_argument(value);
  } catch (const std::logic_error&) {
    throw UsageError(std::string(option) + ": expected local, global or a number, got '" + value + "'");
  }
  front.amplitude = AmplitudeRef::absolute;
}

WaveMode parse_wave_mode(std::string_view text, std::string_view option) {
  if (text == "longitudinal" || text == "L" || text == "P") return WaveMode::longitudinal;
  if (text == "shear" || text == "transverse" || text == "T" || text == "S") return WaveMode::shear;
  throw UsageError(std::string(option) + ": expected longitudinal or shear, got '" + std::string(text) + "'");
}
Signal parse_signal(std::string_view text, std::string_view option) {
  if (text == "displacement") return Signal::displacement;
  if (text == "velocity") return Signal::velocity;
  if (text == "strain") return Signal::strain;
  throw UsageError(std::string(option) + ": expected displacement, velocity or strain, got '" + std::string(text) +
                   "'");
}
Side parse_side(std::string_view text, std::string_view option) {
  if (text == "both") return Side::both;
  if (text == "forward") return Side::forward;
  if (text == "backward") return Side::backward;
  throw UsageError(std::string(option) + ": expected both, forward or backward, got '" + std::string(text) + "'");
}

LineFit fit_line(std::span<const double> x, std::span<const double> y, double reject, double min_tolerance,
                 std::vector<std::uint8_t>& used) {
  const std::size_t n = x.size();
  used.assign(n, 0);
  std::size_t finite = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (std::isfinite(x[k]) && std::isfinite(y[k])) used[k] = 1, ++finite;
  LineFit f = least_squares(x, y, used);
  if (reject > 0) {
    for (int iteration = 0; iteration < 20 && f.points >= 3 && std::isfinite(f.slope); ++iteration) {
      std::vector<double> r(n, kNaN), abs_dev;
      std::vector<double> used_r;
      for (std::size_t k = 0; k < n; ++k)
        if (std::isfinite(x[k]) && std::isfinite(y[k])) {
          r[k] = y[k] - f.intercept - f.slope * x[k];
          if (used[k]) used_r.push_back(r[k]);
        }
      const double centre = median(used_r);
      for (double v : used_r) abs_dev.push_back(std::abs(v - centre));
      const double sigma = 1.4826 * median(abs_dev);
      const double tol = std::max(reject * sigma, min_tolerance);
      std::vector<std::uint8_t> next(n, 0);
      for (std::size_t k = 0; k < n; ++k) next[k] = std::isfinite(r[k]) && std::abs(r[k]) <= tol;
      if (next == used) break;
      const LineFit g = least_squares(x, y, next);
      if (g.points < 3 || !std::isfinite(g.slope)) break;
      used = std::move(next);
      f = g;
    }
  }
  f.rejected = finite - f.points;
  if (f.points < 3 || !std::isfinite(f.slope)) f.rejected = 0;
  return f;
}

double first_crossing(std::span<const double> time, std::span<const double> signal, double level, bool interpolate) {
  for (std::size_t k = 0; k < signal.size(); ++k) {
    if (!(signal[k] >= level)) continue;
    if (k == 0) return kNaN;
    if (!interpolate) return time[k];
    const double s0 = signal[k - 1], s1 = signal[k];
    const double w = s1 > s0 ? (level - s0) / (s1 - s0) : 1.0;
    return time[k - 1] + std::clamp(w, 0.0, 1.0) * (time[k] - time[k - 1]);
  }
  return kNaN;
}

double first_peak(std::span<const double> time, std::span<const double> signal, double level, bool interpolate) {
  std::size_t k = 0;
  while (k < signal.size() && !(signal[k] >= level)) ++k;
  if (k == 0 || k >= signal.size()) return kNaN;
  while (k + 1 < signal.size() && signal[k + 1] > signal[k]) ++k;
  if (k + 1 >= signal.size()) return kNaN;  // still rising at the last frame
  if (!interpolate) return time[k];
  // Vertex of the parabola through (t0, s0), (t1, s1), (t2, s2), in coordinates relative to t1.
  const double a = time[k - 1] - time[k], c = time[k + 1] - time[k];
  const double da = signal[k - 1] - signal[k], dc = signal[k + 1] - signal[k];
  const double den = da * c - dc * a;  // zero when the three points lie on a line
  if (!(std::abs(den) > 0)) return time[k];
  const double shift = 0.5 * (da * c * c - dc * a * a) / den;
  return time[k] + std::clamp(shift, a, c);
}

namespace {

void check_front_options(const FrontOptions& opt) {
  if (opt.directions.empty()) throw UsageError("--direction: no propagation direction given");
  if (!(opt.threshold > 0 && opt.threshold < 1))
    throw UsageError("--threshold: the arrival level is a fraction of the amplitude in (0, 1), got " +
                     number(opt.threshold));
  if (opt.amplitude == AmplitudeRef::absolute && !(opt.amplitude_value > 0 && std::isfinite(opt.amplitude_value)))
    throw UsageError("--amplitude: an absolute amplitude must be a positive number");
  if (!(opt.floor >= 0 && opt.floor < 1)) throw UsageError("--floor: expected a fraction in [0, 1)");
  if (!(opt.bin >= 0)) throw UsageError("--bin: the bin width must be positive (0: automatic)");
  if (!(opt.lateral >= 0)) throw UsageError("--lateral: the half-width must be positive (0: no limit)");
  if (std::isfinite(opt.s_min) && std::isfinite(opt.s_max) && !(opt.s_min < opt.s_max))
    throw UsageError("--range: the nearest distance must be below the farthest");
  if (std::isfinite(opt.s_min) && opt.s_min < 0 && opt.side == Side::both)
    throw UsageError("--range: distances are measured from the source on both sides, so they are >= 0");
  if (!(opt.t_min < opt.t_max)) throw UsageError("--time: the start must be before the end");
  if (!(opt.reject >= 0)) throw UsageError("--reject: expected a number of standard deviations >= 0 (0: keep all)");
  if (opt.signal == Signal::strain && opt.modes.empty())
    throw UsageError("--signal strain cannot tell longitudinal from shear: give --mode");
}

Vec2 body_position(const io::BodyFrame& f, std::size_t i) { return Vec2(f.position[2 * i], f.position[2 * i + 1]); }

// Reference positions and links from the mesh the run carries.
struct RunMesh {
  std::vector<Vec2> reference;
  std::vector<std::array<std::int64_t, 2>> links;
  std::size_t bodies = 0;
};

RunMesh read_run_mesh(const io::Group& run, const io::RunInfo& info, bool cells) {
  RunMesh mesh;
  if (cells) {
    auto m = io::read_cell_mesh(run);
    mesh.reference = std::move(m.centroid);
    mesh.links = std::move(m.beam);
  } else {
    auto m = io::read_node_mesh(run);
    mesh.reference = std::move(m.position);
    mesh.links = std::move(m.bond);
  }
  mesh.bodies = info.mass.size();
  if (mesh.reference.size() != mesh.bodies)
    throw InputError(run.where() + ": the mesh has " + std::to_string(mesh.reference.size()) + " bodies, the run " +
                     std::to_string(mesh.bodies));
  if (mesh.links.empty()) throw InputError(run.where() + ": the mesh has no links (bonds or beams)");
  return mesh;
}

// The frames in the time window (at least 3), and their median spacing.
std::vector<std::size_t> frames_in_window(const io::Group& run, const io::RunInfo& info, const FrontOptions& opt,
                                          WaveMeasurement& out) {
  std::vector<std::size_t> frames;
  for (std::size_t k = 0; k < info.time.size(); ++k)
    if (info.time[k] >= opt.t_min && info.time[k] <= opt.t_max) frames.push_back(k);
  if (frames.size() < 3)
    throw InputError(run.where() + ": " + std::to_string(frames.size()) +
                     " frames in the time window; at least 3 are needed to time a front");
  std::vector<double> dt;
  for (std::size_t k = 1; k < frames.size(); ++k) dt.push_back(info.time[frames[k]] - info.time[frames[k - 1]]);
  out.frame_interval = median(dt);
  out.frames = frames.size();
  return frames;
}

// Homogeneous deformation of the first frame (least squares over its intact links), and the median link
// length (the default bin).
void fit_first_frame(const io::Group& run, const io::BodyFrame& first, const RunMesh& mesh, const FrontOptions& opt,
                     WaveMeasurement& out) {
  const auto& links = mesh.links;
  const auto& reference = mesh.reference;
  const std::size_t bodies = mesh.bodies;
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero(), b = Eigen::Matrix2d::Zero();
  std::vector<double> lengths;
  for (std::size_t k = 0; k < links.size(); ++k) {
    if (!first.intact.empty() && !first.intact[k]) continue;
    const auto i = static_cast<std::size_t>(links[k][0]), j = static_cast<std::size_t>(links[k][1]);
    if (i >= bodies || j >= bodies) throw InputError(run.where() + ": a link names a body out of range");
    const Vec2 d = reference[j] - reference[i], u = body_position(first, j) - body_position(first, i);
    a += u * d.transpose();
    b += d * d.transpose();
    lengths.push_back(u.norm());
  }
  if (lengths.empty()) throw InputError(run.where() + ": no intact link in the first frame");
  if (std::abs(b.determinant()) > 0) out.deformation = a * b.inverse();
  out.bin = opt.bin > 0 ? opt.bin : median(lengths);
}

// Velocity-weighted centroid of the first frame in which something moves.
Vec2 moving_centroid(const io::Group& run, const io::RunInfo& info, const io::BodyFrame& first,
                     const io::Group& bodies_group, std::size_t bodies) {
  Vec2 source(0, 0);
  bool found = false;
  for (std::size_t k = 0; k < info.time.size() && !found; ++k) {
    io::BodyFrame f;
    if (k == 0)
      f.velocity = first.velocity;
    else
      f.velocity = io::read_series_frame<double>(bodies_group, "velocity", static_cast<long long>(k));
    if (f.velocity.size() != 2 * bodies)
      throw InputError(bodies_group.where("velocity") + ": frame size does not match");
    double w = 0;
    Vec2 c(0, 0);
    for (std::size_t i = 0; i < bodies; ++i) {
      const double v2 = f.velocity[2 * i] * f.velocity[2 * i] + f.velocity[2 * i + 1] * f.velocity[2 * i + 1];
      w += v2;
      c += v2 * body_position(first, i);
    }
    if (w > 0 && std::isfinite(w)) {
      source = c / w;
      found = true;
    }
  }
  if (!found) throw InputError(run.where() + ": nothing moves in any frame: there is no pulse to time");
  return source;
}

// Source: given (lab, or reference mapped to the lab by the first frame's affine map p = F r + t, t from
// the centroids), or the velocity-weighted centroid of the first frame in which something moves.
void locate_source(const io::Group& run, const io::RunInfo& info, const io::BodyFrame& first, const RunMesh& mesh,
                   const io::Group& bodies_group, const FrontOptions& opt, WaveMeasurement& out) {
  const std::size_t bodies = mesh.bodies;
  Vec2 mean_p(0, 0), mean_r(0, 0);
  for (std::size_t i = 0; i < bodies; ++i) mean_p += body_position(first, i), mean_r += mesh.reference[i];
  const Vec2 shift = (mean_p - out.deformation * mean_r) / static_cast<double>(bodies);
  if (opt.source) {
    out.source = *opt.source;
    out.source_from = "option";
  } else if (opt.source_reference) {
    out.source = out.deformation * *opt.source_reference + shift;
    out.source_from = "reference";
  } else {
    out.source = moving_centroid(run, info, first, bodies_group, bodies);
    out.source_from = "frames";
  }
}

// Receivers: bodies at their first-frame positions, or link midpoints for the strain signal.
std::vector<Vec2> receiver_positions(const io::BodyFrame& first, const RunMesh& mesh, Signal signal) {
  std::vector<Vec2> where;
  if (signal == Signal::strain) {
    for (const auto& l : mesh.links)
      where.push_back(0.5 * (body_position(first, static_cast<std::size_t>(l[0])) +
                             body_position(first, static_cast<std::size_t>(l[1]))));
  } else {
    for (std::size_t i = 0; i < mesh.bodies; ++i) where.push_back(body_position(first, i));
  }
  return where;
}

// The receivers of direction `dir` in bins of the fitted distance range (shared by both polarisations).
Track base_track(double dir, const std::vector<Vec2>& where, const WaveMeasurement& out, const FrontOptions& opt) {
  const bool radial = is_radial(dir);
  const Vec2 n = radial ? Vec2(1, 0) : Vec2(std::cos(dir), std::sin(dir)), perp(-n.y(), n.x());
  // Signed or folded distance of each receiver; NaN outside the band or on the wrong side.
  std::vector<double> s(where.size(), kNaN);
  double far = 0;
  for (std::size_t r = 0; r < where.size(); ++r) {
    const Vec2 d = where[r] - out.source;
    double value = 0;
    if (radial) {
      value = d.norm();
    } else {
      const double along = d.dot(n), across = d.dot(perp);
      if (opt.lateral > 0 && std::abs(across) > opt.lateral) continue;
      value = along;
      if (opt.side == Side::both)
        value = std::abs(along);
      else if (opt.side == Side::forward && along < 0)
        continue;
      else if (opt.side == Side::backward) {
        if (along > 0) continue;
        value = -along;
      }
    }
    s[r] = value;
    far = std::max(far, value);
  }
  // The near field: a reference distance across planes of normal F^T n is |F^T n| times longer in the lab.
  const double stretch_along = radial ? Eigen::JacobiSVD<Eigen::Matrix2d>(out.deformation).singularValues()(0)
                                      : (out.deformation.transpose() * n).norm();
  const double s_min = std::isfinite(opt.s_min) ? opt.s_min : std::max(0.25 * far, opt.near_field * stretch_along);
  const double s_max = std::isfinite(opt.s_max) ? opt.s_max : 0.95 * far;
  Track base;
  base.direction = dir;
  base.radial = radial;
  base.s_min = s_min;
  base.s_max = s_max;
  const auto bins = static_cast<std::size_t>(std::max(0.0, std::ceil((s_max - s_min) / out.bin)));
  base.bin_distance.assign(bins, 0.0);
  base.bin_count.assign(bins, 0);
  for (std::size_t r = 0; r < where.size(); ++r) {
    if (bins == 0 || !std::isfinite(s[r]) || s[r] < s_min || s[r] >= s_max || (radial && !(s[r] > 0))) continue;
    const auto b = std::min(bins - 1, static_cast<std::size_t>((s[r] - s_min) / out.bin));
    base.receivers.push_back({r, b});
    base.bin_distance[b] += s[r];
    base.bin_count[b] += 1;
  }
  for (std::size_t b = 0; b < bins; ++b)
    if (base.bin_count[b]) base.bin_distance[b] /= static_cast<double>(base.bin_count[b]);
  return base;
}

// One track per (direction, mode). Both polarisations are always tracked (in pairs, longitudinal first):
// the automatic choice and the noise guard compare them.
std::vector<Track> make_tracks(const std::vector<Vec2>& where, const WaveMeasurement& out, const FrontOptions& opt,
                               std::size_t frames) {
  std::vector<Track> tracks;
  const std::vector<WaveMode> modes{WaveMode::longitudinal, WaveMode::shear};
  for (double dir : opt.directions) {
    const bool radial = is_radial(dir);
    const Vec2 n = radial ? Vec2(1, 0) : Vec2(std::cos(dir), std::sin(dir)), perp(-n.y(), n.x());
    const Track base = base_track(dir, where, out, opt);
    const std::size_t bins = base.bin_count.size();
    for (WaveMode mode : modes) {
      Track t = base;
      t.mode = mode;
      t.n = mode == WaveMode::longitudinal ? n : perp;
      if (radial)
        for (const Receiver& r : t.receivers) {
          const Vec2 e = (where[r.index] - out.source).normalized();
          t.unit.push_back(mode == WaveMode::longitudinal ? e : Vec2(-e.y(), e.x()));
        }
      t.signal.assign(bins, std::vector<double>(frames, 0.0));
      tracks.push_back(std::move(t));
    }
  }
  return tracks;
}

// The signal of each receiver, projected on its track's direction (or the link strain change).
double receiver_signal(const io::Group& run, const io::BodyFrame& f, const io::BodyFrame& first, std::size_t links,
                       const Track& t, std::size_t ri, Signal signal) {
  const Receiver& r = t.receivers[ri];
  const Vec2& e = t.radial ? t.unit[ri] : t.n;
  if (signal == Signal::displacement) return (body_position(f, r.index) - body_position(first, r.index)).dot(e);
  if (signal == Signal::velocity) return Vec2(f.velocity[2 * r.index], f.velocity[2 * r.index + 1]).dot(e);
  if (f.strain.size() != links || first.strain.size() != links)
    throw InputError(run.where() + ": the run records no link strain for the strain signal");
  return f.strain[r.index] - first.strain[r.index];
}

// One pass over the frames: each bin's RMS signal per frame, into the tracks. Returns the frames' times.
std::vector<double> record_signals(const io::Group& run, const io::RunInfo& info,
                                   const std::vector<std::size_t>& frames, const io::BodyFrame& first,
                                   const io::Group& bodies_group, const RunMesh& mesh, Signal signal,
                                   std::vector<Track>& tracks) {
  const std::size_t bodies = mesh.bodies;
  std::vector<double> times;
  for (std::size_t fi = 0; fi < frames.size(); ++fi) {
    const std::size_t k = frames[fi];
    // Only the series the signal needs (the trajectory is read one frame at a time).
    io::BodyFrame f;
    if (k == 0) {
      f = first;
    } else {
      const auto frame = static_cast<long long>(k);
      if (signal == Signal::displacement) f.position = io::read_series_frame<double>(bodies_group, "position", frame);
      if (signal == Signal::velocity) f.velocity = io::read_series_frame<double>(bodies_group, "velocity", frame);
      if (signal == Signal::strain) f = io::read_frame(run, frame);  // where the link series live is io's business
    }
    if (signal == Signal::displacement && f.position.size() != 2 * bodies)
      throw InputError(bodies_group.where("position") + ": frame size does not match");
    if (signal == Signal::velocity && f.velocity.size() != 2 * bodies)
      throw InputError(bodies_group.where("velocity") + ": frame size does not match");
    times.push_back(info.time[k]);
    for (Track& t : tracks) {
      std::vector<double> sum(t.bin_count.size(), 0.0);
      for (std::size_t ri = 0; ri < t.receivers.size(); ++ri) {
        const double v = receiver_signal(run, f, first, mesh.links.size(), t, ri, signal);
        sum[t.receivers[ri].bin] += v * v;
      }
      for (std::size_t b = 0; b < sum.size(); ++b)
        if (t.bin_count[b]) t.signal[b][fi] = std::sqrt(sum[b] / static_cast<double>(t.bin_count[b]));
    }
  }
  return times;
}

// Each bin's arrival time (NaN below the floor) and peak signal, into m.
void time_arrivals(const Track& t, const std::vector<double>& times, const FrontOptions& opt, FrontMeasurement& m) {
  for (std::size_t b = 0; b < t.signal.size(); ++b) {
    if (!t.bin_count[b]) continue;
    const auto& sig = t.signal[b];
    const double local = *std::max_element(sig.begin(), sig.end());
    double arrival = kNaN;
    if (local > 0 && local >= opt.floor * m.peak) {
      const double level = opt.amplitude == AmplitudeRef::local ? opt.threshold * local : m.level;
      arrival = opt.arrival == Arrival::threshold ? first_crossing(times, sig, level, opt.interpolate)
                                                  : first_peak(times, sig, level, opt.interpolate);
    }
    m.distance.push_back(t.bin_distance[b]);
    m.arrival.push_back(arrival);
    m.amplitude.push_back(local);
  }
}

// The line through the arrivals, and the speed from it; m.failure says why there is none.
void fit_arrivals(const Track& t, const std::string& what, const FrontOptions& opt, const WaveMeasurement& out,
                  FrontMeasurement& m) {
  m.fit = fit_line(m.distance, m.arrival, opt.reject, 0.5 * out.frame_interval, m.used);
  std::size_t arrivals = 0;
  for (double a : m.arrival) arrivals += std::isfinite(a);
  if (m.fit.points < 3 || !std::isfinite(m.fit.slope)) {
    m.failure = what + ": " + std::to_string(arrivals) + " of " + std::to_string(m.distance.size()) +
                " receiver bins between " + number(t.s_min) + " and " + number(t.s_max) +
                " m saw an arrival; at least 3 are needed (widen --range or --time, or lower --threshold)";
  } else if (!(m.fit.slope > 0)) {
    m.failure = what + ": the arrival times do not grow with distance (slope " + number(m.fit.slope) +
                " s/m): no front travels away from the source at " + number(out.source.x()) + ", " +
                number(out.source.y()) + " m";
  } else {
    m.ok = true;
    m.speed = 1 / m.fit.slope;
    m.speed_stderr = m.fit.slope_stderr / (m.fit.slope * m.fit.slope);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < m.distance.size(); ++k)
      if (m.used[k]) lo = std::min(lo, m.distance[k]), hi = std::max(hi, m.distance[k]);
    m.frame_bound = 1.5 * out.frame_interval * m.speed * m.speed / (hi - lo);
  }
}

// A track's front: arrivals and the fit, or why not (empty range, no signal, round-off only, bad fit).
// `peak` is the track's strongest signal, `other` the other polarisation's.
FrontMeasurement measure_front(const Track& t, double peak, double other, const std::vector<double>& times,
                               const FrontOptions& opt, const WaveMeasurement& out) {
  FrontMeasurement m;
  m.mode = t.mode;
  m.direction = t.direction;
  m.s_min = t.s_min;
  m.s_max = t.s_max;
  m.peak = peak;
  double global = opt.amplitude == AmplitudeRef::absolute ? opt.amplitude_value : m.peak;
  if (opt.amplitude != AmplitudeRef::local) m.level = opt.threshold * global;
  time_arrivals(t, times, opt, m);
  const std::string what = std::string(name(t.mode)) + " front";
  if (!(t.s_min < t.s_max)) {
    m.failure = what + ": the distance range " + number(t.s_min) + " to " + number(t.s_max) +
                " m is empty (the body is too short along this direction, or see --range)";
  } else if (!(m.peak > 0)) {
    m.failure = what + ": no signal in the distance range " + number(t.s_min) + " to " + number(t.s_max) + " m";
  } else if (opt.signal != Signal::strain && m.peak < kNoiseFraction * other) {
    m.failure =
        what + ": no signal beyond round-off (its peak is " + number(m.peak / other) + " of the other polarisation's)";
  } else {
    fit_arrivals(t, what, opt, out, m);
  }
  return m;
}

}  // namespace

WaveMeasurement measure_wave_speeds(const io::Group& run, const FrontOptions& opt) try {
  check_front_options(opt);

  WaveMeasurement out;
  out.signal = opt.signal;
  const io::RunInfo info = io::read_run_info(run);
  out.model = info.model;
  const bool cells = info.model == "dem";
  const RunMesh mesh = read_run_mesh(run, info, cells);
  const std::vector<std::size_t> frames = frames_in_window(run, info, opt, out);

  // Baseline: the first frame of the run.
  const io::BodyFrame first = io::read_frame(run, 0);
  const io::Group bodies_group = run.group(cells ? "particles/cells" : "particles/nodes");
  fit_first_frame(run, first, mesh, opt, out);
  locate_source(run, info, first, mesh, bodies_group, opt, out);
  const std::vector<Vec2> where = receiver_positions(first, mesh, opt.signal);
  std::vector<Track> tracks = make_tracks(where, out, opt, frames.size());
  const std::vector<double> times = record_signals(run, info, frames, first, bodies_group, mesh, opt.signal, tracks);

  // ---- arrivals and fits ----
  // Peaks per track, for the automatic choice of modes.
  const auto requested = [&](WaveMode mode) {
    return opt.modes.empty() || std::find(opt.modes.begin(), opt.modes.end(), mode) != opt.modes.end();
  };
  std::vector<double> peaks;
  for (const Track& t : tracks) {
    double p = 0;
    for (const auto& sig : t.signal)
      for (double v : sig)
        if (std::isfinite(v)) p = std::max(p, v);
    peaks.push_back(p);
  }
  for (std::size_t ti = 0; ti < tracks.size(); ++ti) {
    const Track& t = tracks[ti];
    if (!requested(t.mode)) continue;
    // The other polarisation of the same direction.
    const double other = peaks[ti % 2 == 0 ? ti + 1 : ti - 1];
    if (opt.modes.empty() && (!(peaks[ti] > 0) || peaks[ti] < opt.auto_mode_fraction * other)) continue;
    out.fronts.push_back(measure_front(t, peaks[ti], other, times, opt, out));
  }
  return out;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the wave-speed measurement of " + run.file());
}

}  // namespace frac::analysis
