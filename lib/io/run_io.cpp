#include "io/run_io.hpp"

#include <cmath>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/checksum.hpp"
#include "io/hdf5_copy.hpp"
#include "io/mesh_io.hpp"

namespace frac::io {
namespace {
const char* body_group(bool cells) { return cells ? "particles/cells" : "particles/nodes"; }
const char* link_group(bool cells) { return cells ? "connectivity/beams" : "connectivity/bonds"; }
const char* breaks_name(bool cells) { return cells ? "beam_breaks" : "bond_breaks"; }
std::vector<BreakEvent> read_breaks_at(const Group& root, bool cells);
constexpr const char* kObservableNames = "observable_names";  // in a checkpoint's copy of the output

std::uint64_t breaks_checksum(const std::vector<BreakEvent>& breaks) {
  Checksum c;
  for (const BreakEvent& e : breaks) {
    c.add_value(e.step);
    c.add_value(e.time);
    c.add_value(e.index);
    c.add_value(e.mode);
  }
  return c.h;
}

}  // namespace

RunWriter::RunWriter(Group& root, const mesh::CellMesh& mesh, std::span<const double> mass,
                     std::span<const double> inertia)
    : root_(root),
      cells_(true),
      bodies_(mesh.cells()),
      links_(mesh.beams()),
      specs_(standard_trajectory(true, bodies_, links_)) {
  root_.set_attr("model", "dem");
  write_mesh(root_, mesh);
  Group cells = root_.group(body_group(true));
  cells.write("mass", mass, {bodies_}, "kg");
  cells.write("inertia", inertia, {bodies_}, "kg m^2");
}

RunWriter::RunWriter(Group& root, const mesh::NodeMesh& mesh, std::span<const double> mass)
    : root_(root),
      cells_(false),
      bodies_(mesh.position.size()),
      links_(mesh.bond.size()),
      specs_(standard_trajectory(false, bodies_, links_)) {
  root_.set_attr("model", "rubber");
  write_mesh(root_, mesh);
  Group nodes = root_.group(body_group(false));
  nodes.write("mass", mass, {bodies_}, "kg");
}

std::vector<SeriesSpec> standard_trajectory(bool cells, std::size_t bodies, std::size_t links) {
  const std::string b = body_group(cells);
  // The link series sit in a subgroup: the node mesh already has a static `intact` (the notch).
  const std::string l = std::string(link_group(cells)) + "/trajectory";
  std::vector<SeriesSpec> specs{{b, "position", {bodies, 2}, "m", false}, {b, "velocity", {bodies, 2}, "m s-1", false}};
  if (cells) {
    specs.push_back({b, "angle", {bodies}, "rad", false});
    specs.push_back({b, "angular_velocity", {bodies}, "rad s-1", false});
  }
  specs.push_back({l, "intact", {links}, "", true});
  specs.push_back({l, "strain", {links}, "1", false});
  return specs;
}

void RunWriter::declare_trajectory(std::vector<SeriesSpec> specs) {
  if (!series_.empty()) throw std::logic_error("RunWriter: the trajectory is declared before its first frame");
  specs_ = std::move(specs);
}

void RunWriter::create_trajectory() {
  for (const SeriesSpec& s : specs_) {
    Group g = root_.has(s.group) ? root_.group(s.group) : root_.create_group(s.group);
    series_.push_back(
        std::make_unique<SeriesWriter>(g, s.name, s.dims, s.unit, s.flags ? SeriesType::uint8 : SeriesType::float64));
  }
}

void RunWriter::append(std::size_t k, std::int64_t step, double time, std::span<const double> values) {
  if (series_.empty()) create_trajectory();
  series_.at(k)->append(step, time, values);
}

void RunWriter::append(std::size_t k, std::int64_t step, double time, std::span<const std::uint8_t> values) {
  if (series_.empty()) create_trajectory();
  series_.at(k)->append(step, time, values);
}

void RunWriter::write_frame(const BodyFrame& f) {
  std::size_t k = 0;
  append(k++, f.step, f.time, std::span<const double>(f.position));
  append(k++, f.step, f.time, std::span<const double>(f.velocity));
  if (cells_) {
    append(k++, f.step, f.time, std::span<const double>(f.angle));
    append(k++, f.step, f.time, std::span<const double>(f.angular_velocity));
  }
  append(k++, f.step, f.time, std::span<const std::uint8_t>(f.intact));
  append(k++, f.step, f.time, std::span<const double>(f.strain));
}

SeriesWriter& RunWriter::observable(const std::string& name, std::vector<hsize_t> dims, std::string_view unit) {
  auto it = observables_.find(name);
  if (it == observables_.end()) {
    Group obs = root_.has("observables") ? root_.group("observables") : root_.create_group("observables");
    it = observables_.emplace(name, std::make_unique<SeriesWriter>(obs, name, std::move(dims), unit)).first;
  }
  return *it->second;
}

void RunWriter::observe(const std::string& name, std::int64_t step, double time, std::span<const double> value,
                        std::string_view unit) {
  std::vector<hsize_t> dims;
  if (value.size() != 1) dims.push_back(value.size());
  observable(name, std::move(dims), unit).append(step, time, value);
}

void RunWriter::flush() {
  for (const auto& series : series_) series->flush();
  for (auto& [name, series] : observables_) series->flush();
}

void RunWriter::finish() {
  flush();
  write_breaks(root_);
}

void RunWriter::copy_progress(Group& to) {
  flush();
  const auto copy = [&](const std::string& path, const SeriesWriter& series) {
    copy_group(root_, path, to);
    to.group(path).set_attr("checksum", static_cast<std::int64_t>(series.checksum()));
  };
  for (std::size_t k = 0; k < series_.size(); ++k) copy(specs_[k].group + "/" + specs_[k].name, *series_[k]);
  std::vector<std::string> names;
  for (auto& [name, series] : observables_) {
    copy("observables/" + name, *series);
    names.push_back(name);
  }
  to.write_strings(kObservableNames, names);
  write_breaks(to);
  to.group(std::string("observables/") + breaks_name(cells_))
      .set_attr("checksum", static_cast<std::int64_t>(breaks_checksum(breaks_)));
}

void RunWriter::replay(const Group& from) {
  if (!specs_.empty() && from.has(specs_.front().group + "/" + specs_.front().name)) {
    create_trajectory();
    for (std::size_t k = 0; k < series_.size(); ++k) series_[k]->replay(from.group(specs_[k].group), specs_[k].name);
  }
  if (!from.has(kObservableNames))
    throw InputError(from.where() + ": not a checkpoint's copy of a run (no observable_names)");
  for (const std::string& name : from.read_strings(kObservableNames)) {
    const Group obs = from.group("observables");
    const SeriesInfo info = read_series_info(obs, name);
    const Group series = obs.group(name);
    const std::string unit = series.has_attr("unit", "value") ? series.attr_string("unit", "value") : "";
    observable(name, info.frame_dims, unit).replay(obs, name);
  }
  breaks_ = read_breaks_at(from, cells_);
  const Group breaks = from.group(std::string("observables/") + breaks_name(cells_));
  if (!breaks.has_attr("checksum") ||
      breaks.attr_int("checksum") != static_cast<std::int64_t>(breaks_checksum(breaks_)))
    throw InputError(breaks.where() + ": damaged (the events do not match their checksum)");
}

void RunWriter::write_breaks(Group& root) const {
  Group obs = root.has("observables") ? root.group("observables") : root.create_group("observables");
  Group g = obs.create_group(breaks_name(cells_));
  std::vector<std::int64_t> step, index;
  std::vector<double> time;
  std::vector<std::uint8_t> mode;
  for (const auto& e : breaks_) {
    step.push_back(e.step);
    time.push_back(e.time);
    index.push_back(e.index);
    mode.push_back(e.mode);
  }
  const hsize_t k = breaks_.size();
  g.write("step", std::span<const std::int64_t>(step), {k});
  g.write("time", std::span<const double>(time), {k}, "s");
  g.write("index", std::span<const std::int64_t>(index), {k});
  g.write("mode", std::span<const std::uint8_t>(mode), {k});
  g.set_attr("mode_meaning", cells_ ? "1 the stretching term of the breaking rule dominated, 2 the bending term"
                                    : "1 separation past u_c");
}

RunInfo read_run_info(const Group& root) {
  RunInfo info;
  if (!root.has_attr("model")) throw InputError(root.where() + ": not a run file (no 'model' attribute)");
  info.model = root.attr_string("model");
  if (info.model != "dem" && info.model != "rubber")
    throw InputError(root.where() + ": unknown model '" + info.model + "'");
  const bool cells = info.model == "dem";
  const Group bodies = root.group(body_group(cells));
  info.mass = bodies.read<double>("mass", nullptr, 1);
  if (cells) info.inertia = bodies.read<double>("inertia", nullptr, 1);
  const SeriesInfo s = read_series_info(bodies, "position");
  info.step = s.step;
  info.time = s.time;
  if (info.step.empty()) throw InputError(bodies.where("position") + ": the run holds no frames");
  return info;
}

BodyFrame read_frame(const Group& root, long long frame) {
  const RunInfo info = read_run_info(root);
  const bool cells = info.model == "dem";
  const Group bodies = root.group(body_group(cells));
  const Group links = root.group(std::string(link_group(cells)) + "/trajectory");
  const auto frames = static_cast<long long>(info.step.size());
  const long long k = frame < 0 ? frames + frame : frame;
  BodyFrame f;
  f.position = read_series_frame<double>(bodies, "position", frame);
  if (k >= 0 && k < frames) {
    f.step = info.step[static_cast<std::size_t>(k)];
    f.time = info.time[static_cast<std::size_t>(k)];
  }
  f.velocity = read_series_frame<double>(bodies, "velocity", frame);
  if (cells) {
    f.angle = read_series_frame<double>(bodies, "angle", frame);
    f.angular_velocity = read_series_frame<double>(bodies, "angular_velocity", frame);
  }
  f.intact = read_series_frame<std::uint8_t>(links, "intact", frame);
  f.strain = read_series_frame<double>(links, "strain", frame);
  const std::size_t n = info.mass.size();
  if (f.position.size() != 2 * n || f.velocity.size() != 2 * n || (cells && f.angle.size() != n))
    throw InputError(bodies.where("position") + ": frame size does not match the mass dataset");
  return f;
}

long long frame_at_time(const RunInfo& info, double t) {
  long long best = 0;
  for (std::size_t k = 0; k < info.time.size(); ++k)
    if (std::abs(info.time[k] - t) < std::abs(info.time[static_cast<std::size_t>(best)] - t))
      best = static_cast<long long>(k);
  return best;
}

std::vector<BreakEvent> read_breaks(const Group& root) {
  return read_breaks_at(root, read_run_info(root).model == "dem");
}

namespace {
std::vector<BreakEvent> read_breaks_at(const Group& root, bool cells) {
  std::vector<BreakEvent> out;
  const std::string path = std::string("observables/") + breaks_name(cells);
  if (!root.has(path)) return out;
  const Group g = root.group(path);
  const auto step = g.read<std::int64_t>("step", nullptr, 1);
  const auto time = g.read<double>("time", nullptr, 1);
  const auto index = g.read<std::int64_t>("index", nullptr, 1);
  const auto mode = g.read<std::uint8_t>("mode", nullptr, 1);
  if (time.size() != step.size() || index.size() != step.size() || mode.size() != step.size())
    throw InputError(g.where() + ": step, time, index and mode differ in length");
  for (std::size_t k = 0; k < step.size(); ++k) out.push_back({step[k], time[k], index[k], mode[k]});
  return out;
}

}  // namespace

}  // namespace frac::io
