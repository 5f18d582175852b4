#include "analysis/observable_table.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "core/error.hpp"
#include "io/provenance_text.hpp"
#include "io/run_io.hpp"

namespace frac::analysis {

std::size_t ObservableTable::column(const std::string& name, const std::string& file) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw InputError(file + ": no observable '" + name + "' in the table");
  return static_cast<std::size_t>(it - names.begin());
}

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

namespace {
std::vector<std::string> list_scalar_observables(const io::Group& obs) {
  std::vector<std::string> names;
  H5G_info_t info;
  H5Gget_info(obs.id(), &info);
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    char buf[256];
    H5Lget_name_by_idx(obs.id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, buf, sizeof buf, H5P_DEFAULT);
    const std::string name(buf);
    if (!obs.has(name + "/value")) continue;
    std::vector<hsize_t> dims;
    obs.group(name).read<double>("value", &dims);
    if (dims.size() == 1) names.push_back(name);
  }
  return names;
}
}  // namespace

ObservableTable read_observables(const io::Group& root, const std::vector<std::string>& wanted) {
  const io::Group obs = root.group("observables");
  ObservableTable t;
  t.names = wanted.empty() ? list_scalar_observables(obs) : wanted;
  for (const auto& name : t.names) {
    if (!obs.has(name)) throw InputError(obs.where(name) + ": no such observable");
    const io::Group g = obs.group(name);
    const auto time = g.read<double>("time", nullptr, 1);
    auto value = g.read<double>("value", nullptr, 1);
    if (t.time.empty()) t.time = time;
    if (time != t.time)
      throw InputError(g.where() + ": sampled at other times than " + t.names.front() + "; fit them separately");
    t.units.push_back(g.has_attr("unit", "value") ? g.attr_string("unit", "value") : "");
    t.columns.push_back(std::move(value));
  }
  return t;
}

void write_csv(const ObservableTable& t, std::ostream& out, const std::string& provenance) {
  out << io::csv_comment(provenance) << "time_s";
  for (std::size_t c = 0; c < t.names.size(); ++c)
    out << "," << t.names[c] << (t.units[c].empty() || t.units[c] == "1" ? "" : "_" + t.units[c]);
  out << "\n" << std::setprecision(17);  // round trip: an energy drift of 1e-12 of a pre-stretched sheet must survive
  for (std::size_t r = 0; r < t.time.size(); ++r) {
    out << t.time[r];
    for (const auto& col : t.columns) out << "," << col[r];
    out << "\n";
  }
}

std::vector<std::uint8_t> select_rows(const ObservableTable& t, const std::string& condition, double after,
                                      const std::string& file) {
  std::vector<std::uint8_t> rows(t.time.size(), 0);
  std::size_t column = 0;
  char op = 0;
  double threshold = 0;
  if (!condition.empty()) {
    const auto at = condition.find_first_of("<>");
    if (at == std::string::npos)
      throw UsageError("--where: expected NAME>VALUE or NAME<VALUE, got '" + condition + "'");
    column = t.column(condition.substr(0, at), file);
    op = condition[at];
    try {
      threshold = std::stod(condition.substr(at + 1));
    } catch (const std::exception&) {
      throw UsageError("--where: '" + condition.substr(at + 1) + "' is not a number");
    }
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    bool keep = t.time[r] > after;
    if (op == '>') keep = keep && t.columns[column][r] > threshold;
    if (op == '<') keep = keep && t.columns[column][r] < threshold;
    rows[r] = keep ? 1 : 0;
  }
  return rows;
}

LineFit fit_columns(const ObservableTable& t, const std::string& y, const std::string& x,
                    const std::vector<std::uint8_t>& rows, const std::string& file) {
  const auto& cx = t.columns[t.column(x, file)];
  const auto& cy = t.columns[t.column(y, file)];
  std::vector<double> xs, ys;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (rows[r]) {
      xs.push_back(cx[r]);
      ys.push_back(cy[r]);
    }
  std::vector<std::uint8_t> used;
  const LineFit f = fit_line(xs, ys, 0.0, 0.0, used);
  if (f.points < 3)
    throw InputError(file + ": only " + std::to_string(f.points) + " samples selected for the fit of " + y + " on " +
                     x);
  return f;
}

std::string run_parameter(const io::Group& root, const std::string& name) {
  for (const char* tool : {"dem-run", "rubber-run"}) {
    const std::string path = std::string("parameters/") + tool;
    if (root.has(path) && root.group(path).has_attr(name)) return root.group(path).attr_string(name);
  }
  throw InputError(root.where("parameters") + ": no parameter '" + name + "'");
}

PositionDifference compare_final_positions(const io::Group& run, const io::Group& reference, const std::string& file,
                                           const std::string& reference_file) {
  const io::BodyFrame a = io::read_frame(run, -1);
  const io::BodyFrame b = io::read_frame(reference, -1);
  if (a.position.size() != b.position.size())
    throw InputError(file + " and " + reference_file + ": different numbers of bodies (" +
                     std::to_string(a.position.size() / 2) + " and " + std::to_string(b.position.size() / 2) + ")");
  PositionDifference d;
  d.time = a.time;
  d.reference_time = b.time;
  double sum = 0;
  for (std::size_t k = 0; k + 1 < a.position.size(); k += 2) {
    const double dist = std::hypot(a.position[k] - b.position[k], a.position[k + 1] - b.position[k + 1]);
    sum += dist * dist;
    d.max = std::max(d.max, dist);
  }
  d.rms = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(a.position.size() / 2, 1)));
  return d;
}

}  // namespace frac::analysis
