#include "io/speeds_io.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/provenance_text.hpp"

namespace frac::io {
namespace {

std::string amplitude_unit(const std::string& signal) {
  return signal == "displacement" ? "m" : signal == "velocity" ? "m s-1" : "1";
}

void scalar(Group& g, const std::string& name, double v, const std::string& unit) {
  g.write(name, std::span<const double>(&v, 1), {}, unit);
}

double read_scalar(const Group& g, const std::string& name) {
  const auto v = g.read<double>(name);
  if (v.size() != 1) throw InputError(g.where(name) + ": expected one value");
  return v[0];
}

template <class T, class F>
std::vector<T> column(const std::vector<MeasuredSpeed>& m, F f) {
  std::vector<T> out;
  for (const auto& x : m) out.push_back(f(x));
  return out;
}

std::vector<double> read_column(const Group& g, const std::string& name, std::size_t n) {
  auto v = g.read<double>(name, nullptr, 1);
  if (v.size() != n) throw InputError(g.where(name) + ": expected " + std::to_string(n) + " values");
  return v;
}

// Front k's arrivals against distance, under /speeds/measured/fronts/<k>.
void write_front(Group& m, std::size_t k, const MeasuredSpeed& x, const std::string& signal) {
  Group f = m.create_group("fronts/" + std::to_string(k));
  f.set_attr("label", x.label);
  const hsize_t b = x.distance.size();
  if (x.arrival.size() != b || x.amplitude.size() != b || x.used.size() != b)
    throw RuntimeError(f.where() + ": distance, arrival, amplitude and used differ in length");
  f.write("distance", std::span<const double>(x.distance), {b}, "m");
  f.write("arrival_time", std::span<const double>(x.arrival), {b}, "s");
  f.write("amplitude", std::span<const double>(x.amplitude), {b}, amplitude_unit(signal));
  f.write("used", std::span<const std::uint8_t>(x.used), {b});
}

// /speeds/measured: the run's measurement, one row per front, and each front's arrivals under fronts/<k>.
void write_measured(Group& s, const SpeedsRecord& r) {
  Group m = s.create_group("measured");
  m.set_attr("model", r.model);
  m.set_attr("signal", r.signal);
  m.set_attr("arrival", r.arrival);
  m.set_attr("amplitude", r.amplitude);
  m.set_attr("source_from", r.source_from);
  scalar(m, "threshold", r.threshold, "1");
  m.write("source", std::span<const double>(r.source), {2}, "m");
  scalar(m, "frame_interval", r.frame_interval, "s");
  const std::int64_t frames = r.frames;
  m.write("frames", std::span<const std::int64_t>(&frames, 1), {});
  scalar(m, "bin", r.bin, "m");
  m.write("deformation", std::span<const double>(r.deformation), {2, 2}, "1");
  const hsize_t n = r.measured.size();
  m.write_strings("label", column<std::string>(r.measured, [](const auto& x) { return x.label; }));
  m.write_strings("mode", column<std::string>(r.measured, [](const auto& x) { return x.mode; }));
  m.write_strings("failure", column<std::string>(r.measured, [](const auto& x) { return x.failure; }));
  const auto ok = column<std::uint8_t>(r.measured, [](const auto& x) { return std::uint8_t(x.ok ? 1 : 0); });
  m.write("ok", std::span<const std::uint8_t>(ok), {n});
  const auto put = [&](const char* name, auto f, const char* unit) {
    const auto v = column<double>(r.measured, f);
    m.write(name, std::span<const double>(v), {n}, unit);
  };
  put(
      "direction", [](const auto& x) { return x.direction; }, "rad");
  put(
      "speed", [](const auto& x) { return x.speed; }, "m s-1");
  put(
      "speed_stderr", [](const auto& x) { return x.speed_stderr; }, "m s-1");
  put(
      "intercept", [](const auto& x) { return x.intercept; }, "s");
  put(
      "residual_rms", [](const auto& x) { return x.residual_rms; }, "s");
  put(
      "frame_bound", [](const auto& x) { return x.frame_bound; }, "m s-1");
  put(
      "range_min", [](const auto& x) { return x.range_min; }, "m");
  put(
      "range_max", [](const auto& x) { return x.range_max; }, "m");
  put(
      "predicted", [](const auto& x) { return x.predicted; }, "m s-1");
  put(
      "deviation", [](const auto& x) { return x.deviation; }, "1");
  put(
      "lattice_predicted", [](const auto& x) { return x.lattice_predicted; }, "m s-1");
  put(
      "lattice_deviation", [](const auto& x) { return x.lattice_deviation; }, "1");
  const auto points = column<std::int64_t>(r.measured, [](const auto& x) { return x.points; });
  const auto rejected = column<std::int64_t>(r.measured, [](const auto& x) { return x.rejected; });
  m.write("points", std::span<const std::int64_t>(points), {n});
  m.write("rejected", std::span<const std::int64_t>(rejected), {n});
  for (std::size_t k = 0; k < r.measured.size(); ++k) write_front(m, k, r.measured[k], r.signal);
}

// /speeds/predicted: one row per direction, the theory's parameters and (Mooney-Rivlin) stresses.
void write_predicted(Group& s, const SpeedsRecord& r) {
  Group p = s.create_group("predicted");
  p.set_attr("theory", r.theory);
  p.set_attr("formulas", r.formulas);
  const hsize_t d = r.predicted.size();
  std::vector<double> dir, cl, cs, clr, csr;
  std::vector<std::string> labels;
  for (const auto& x : r.predicted) {
    labels.push_back(x.label);
    dir.push_back(x.direction);
    cl.push_back(x.longitudinal);
    cs.push_back(x.shear);
    clr.push_back(x.longitudinal_reference);
    csr.push_back(x.shear_reference);
  }
  p.write_strings("label", labels);
  p.write("direction", std::span<const double>(dir), {d}, "rad");
  p.write("longitudinal", std::span<const double>(cl), {d}, "m s-1");
  p.write("shear", std::span<const double>(cs), {d}, "m s-1");
  p.write("longitudinal_reference", std::span<const double>(clr), {d}, "m s-1");
  p.write("shear_reference", std::span<const double>(csr), {d}, "m s-1");
  Group params = p.create_group("parameters");
  for (const auto& v : r.parameters) scalar(params, v.name, v.value, v.unit);
  if (!r.stress.empty()) {
    Group st = p.create_group("stress");
    for (const auto& v : r.stress) scalar(st, v.name, v.value, v.unit);
  }
}

// The scalar attributes and per-front columns of /speeds/measured.
void read_measured_header(const Group& m, SpeedsRecord& r) {
  r.model = m.attr_string("model");
  r.signal = m.attr_string("signal");
  r.arrival = m.attr_string("arrival");
  r.amplitude = m.attr_string("amplitude");
  r.source_from = m.attr_string("source_from");
  r.threshold = read_scalar(m, "threshold");
  const auto src = read_column(m, "source", 2);
  r.source = {src[0], src[1]};
  r.frame_interval = read_scalar(m, "frame_interval");
  const auto frames = m.read<std::int64_t>("frames");
  if (frames.size() != 1) throw InputError(m.where("frames") + ": expected one value");
  r.frames = frames[0];
  r.bin = read_scalar(m, "bin");
  const auto f = m.read<double>("deformation", nullptr, 2, 2);
  if (f.size() != 4) throw InputError(m.where("deformation") + ": expected a 2x2 matrix");
  r.deformation = {f[0], f[1], f[2], f[3]};
}

// Front k's arrivals, /speeds/measured/fronts/<k>.
void read_front(const Group& m, std::size_t k, MeasuredSpeed& x) {
  const Group g = m.group("fronts/" + std::to_string(k));
  x.distance = g.read<double>("distance", nullptr, 1);
  const std::size_t b = x.distance.size();
  x.arrival = read_column(g, "arrival_time", b);
  x.amplitude = read_column(g, "amplitude", b);
  x.used = g.read<std::uint8_t>("used", nullptr, 1);
  if (x.used.size() != b) throw InputError(g.where("used") + ": expected " + std::to_string(b) + " values");
}

// /speeds/measured: the header, then one MeasuredSpeed per row of the per-front columns.
void read_measured(const Group& m, SpeedsRecord& r) {
  read_measured_header(m, r);
  const auto label = m.read_strings("label");
  const std::size_t n = label.size();
  const auto mode = m.read_strings("mode");
  const auto failure = m.read_strings("failure");
  const auto ok = m.read<std::uint8_t>("ok", nullptr, 1);
  const auto points = m.read<std::int64_t>("points", nullptr, 1);
  const auto rejected = m.read<std::int64_t>("rejected", nullptr, 1);
  if (mode.size() != n || failure.size() != n || ok.size() != n || points.size() != n || rejected.size() != n)
    throw InputError(m.where() + ": the per-front datasets differ in length");
  const auto direction = read_column(m, "direction", n), speed = read_column(m, "speed", n),
             stderr_ = read_column(m, "speed_stderr", n), intercept = read_column(m, "intercept", n),
             rms = read_column(m, "residual_rms", n), bound = read_column(m, "frame_bound", n),
             lo = read_column(m, "range_min", n), hi = read_column(m, "range_max", n),
             predicted = read_column(m, "predicted", n), deviation = read_column(m, "deviation", n),
             lattice_predicted = read_column(m, "lattice_predicted", n),
             lattice_deviation = read_column(m, "lattice_deviation", n);
  for (std::size_t k = 0; k < n; ++k) {
    MeasuredSpeed x;
    x.label = label[k];
    x.mode = mode[k];
    x.failure = failure[k];
    x.ok = ok[k] != 0;
    x.direction = direction[k];
    x.speed = speed[k];
    x.speed_stderr = stderr_[k];
    x.intercept = intercept[k];
    x.residual_rms = rms[k];
    x.frame_bound = bound[k];
    x.points = points[k];
    x.rejected = rejected[k];
    x.range_min = lo[k];
    x.range_max = hi[k];
    x.predicted = predicted[k];
    x.deviation = deviation[k];
    x.lattice_predicted = lattice_predicted[k];
    x.lattice_deviation = lattice_deviation[k];
    read_front(m, k, x);
    r.measured.push_back(std::move(x));
  }
}

// /speeds/predicted: speeds per direction, then parameters and stresses by the names the writer uses, in
// its order.
void read_predicted(const Group& p, SpeedsRecord& r) {
  r.theory = p.attr_string("theory");
  r.formulas = p.attr_string("formulas");
  const auto dir = p.read<double>("direction", nullptr, 1);
  const std::size_t d = dir.size();
  const auto cl = read_column(p, "longitudinal", d), cs = read_column(p, "shear", d),
             clr = read_column(p, "longitudinal_reference", d), csr = read_column(p, "shear_reference", d);
  const auto labels = p.read_strings("label");
  if (labels.size() != d) throw InputError(p.where("label") + ": expected " + std::to_string(d) + " labels");
  for (std::size_t k = 0; k < d; ++k) r.predicted.push_back({labels[k], dir[k], cl[k], cs[k], clr[k], csr[k]});
  const auto named = [](const Group& g, std::initializer_list<const char*> names, std::vector<NamedValue>& out) {
    for (const char* nm : names)
      if (g.has(nm)) out.push_back({nm, read_scalar(g, nm), g.has_attr("unit", nm) ? g.attr_string("unit", nm) : ""});
  };
  named(p.group("parameters"), {"a", "b", "density", "stretch_x", "stretch_y", "young", "poisson"}, r.parameters);
  if (p.has("stress")) named(p.group("stress"), {"piola_xx", "piola_yy", "cauchy_xx", "cauchy_yy"}, r.stress);
}

}  // namespace

void write_speeds(Group& root, const SpeedsRecord& r) {
  Group s = root.create_group("speeds");
  s.set_attr("origin", r.origin);
  s.set_attr("theory", r.theory);
  s.set_attr("comparison", r.comparison);
  if (r.origin == "run") write_measured(s, r);
  if (!r.theory.empty()) write_predicted(s, r);
  if (!r.lattice_regime.empty()) {
    Group l = s.create_group("lattice");
    l.set_attr("regime", r.lattice_regime);
    l.set_attr("message", r.lattice_message);
    l.write("bond_angle", std::span<const double>(r.bond_angle), {r.bond_angle.size()}, "rad");
    l.write("bond_length", std::span<const double>(r.bond_length), {r.bond_length.size()}, "m");
  }
}

SpeedsRecord read_speeds(const Group& root) {
  if (!root.has("speeds")) throw InputError(root.file() + ": holds no /speeds group");
  const Group s = root.group("speeds");
  SpeedsRecord r;
  r.origin = s.attr_string("origin");
  r.theory = s.attr_string("theory");
  r.comparison = s.attr_string("comparison");
  if (s.has("measured")) read_measured(s.group("measured"), r);
  if (s.has("predicted")) read_predicted(s.group("predicted"), r);
  if (s.has("lattice")) {
    const Group l = s.group("lattice");
    r.lattice_regime = l.attr_string("regime");
    r.lattice_message = l.attr_string("message");
    r.bond_angle = l.read<double>("bond_angle", nullptr, 1);
    r.bond_length = l.read<double>("bond_length", nullptr, 1);
  }
  return r;
}

std::string speeds_text(const SpeedsRecord& r, const std::string& provenance) {
  std::ostringstream out;
  out << csv_comment(provenance);
  out.precision(10);
  const auto num = [&](const std::string& key, double v) { out << key << " " << v << "\n"; };
  const auto txt = [&](const std::string& key, const std::string& v) {
    if (!v.empty()) out << key << " " << v << "\n";
  };
  txt("origin", r.origin);
  if (r.origin == "run") {
    txt("model", r.model);
    txt("signal", r.signal);
    txt("arrival", r.arrival);
    txt("amplitude", r.amplitude);
    num("threshold", r.threshold);
    num("source.x", r.source[0]);
    num("source.y", r.source[1]);
    txt("source.from", r.source_from);
    num("frames", static_cast<double>(r.frames));
    num("frame_interval", r.frame_interval);
    num("bin", r.bin);
    num("deformation.xx", r.deformation[0]);
    num("deformation.xy", r.deformation[1]);
    num("deformation.yx", r.deformation[2]);
    num("deformation.yy", r.deformation[3]);
    for (const auto& m : r.measured) {
      const std::string k = "measured." + m.label + ".";
      if (!m.ok) {
        txt(k + "failure", m.failure);
        continue;
      }
      num(k + "speed", m.speed);
      num(k + "stderr", m.speed_stderr);
      num(k + "frame_bound", m.frame_bound);
      num(k + "points", static_cast<double>(m.points));
      num(k + "rejected", static_cast<double>(m.rejected));
      num(k + "range_min", m.range_min);
      num(k + "range_max", m.range_max);
      if (std::isfinite(m.predicted)) num(k + "predicted", m.predicted);
      if (std::isfinite(m.deviation)) num(k + "deviation", m.deviation);
      if (std::isfinite(m.lattice_predicted)) num(k + "lattice_predicted", m.lattice_predicted);
      if (std::isfinite(m.lattice_deviation)) num(k + "lattice_deviation", m.lattice_deviation);
    }
  }
  if (!r.theory.empty()) {
    txt("theory", r.theory);
    for (const auto& v : r.parameters) num("theory." + v.name, v.value);
    for (const auto& p : r.predicted) {
      const std::string k = "predicted." + p.label + ".";
      num(k + "longitudinal", p.longitudinal);
      num(k + "shear", p.shear);
      if (std::isfinite(p.longitudinal_reference)) num(k + "longitudinal_reference", p.longitudinal_reference);
      if (std::isfinite(p.shear_reference)) num(k + "shear_reference", p.shear_reference);
    }
    for (const auto& v : r.stress) num("stress." + v.name, v.value);
  }
  if (!r.lattice_regime.empty()) {
    txt("lattice.regime", r.lattice_regime);
    for (std::size_t k = 0; k < r.bond_length.size(); ++k) {
      std::ostringstream key;
      key << "lattice.bond_length." << std::lround(r.bond_angle[k] * 180 / std::numbers::pi) << "deg";
      num(key.str(), r.bond_length[k]);
    }
    txt("lattice.message", r.lattice_message);
  }
  txt("comparison", r.comparison);
  return out.str();
}

void write_speeds_file(const std::string& path, const SpeedsRecord& r, const ToolRun& run, bool text) {
  if (text) {
    write_file_atomically(path, speeds_text(r, provenance_line(run)));
    return;
  }
  OutputFile out(path);
  write_header(out.root(), "speeds", run, out.uuid());
  write_speeds(out.root(), r);
  out.commit();
}

}  // namespace frac::io
