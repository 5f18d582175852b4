#include "render/run_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/series.hpp"

namespace frac::render {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr Rgb kPlainFill{0.76, 0.81, 0.88};  // cells and nodes without a field
constexpr Rgb kPlainLink{0.40, 0.40, 0.40};  // links of a mesh (no strain)
constexpr Rgb kBrokenMark{0.55, 0.0, 0.05};  // broken-link crosses in "broken" mode

std::string sci(double v, int digits = 3) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// Reads a parameter attribute written as text (or as a number) from /parameters/<tool>.
std::optional<std::string> parameter(const io::Group& root, const std::string& tool, const std::string& key) {
  const std::string object = "parameters/" + tool;
  if (!root.has(object) || !root.has_attr(key, object)) return std::nullopt;
  try {
    return root.attr_string(key, object);
  } catch (const InputError&) {
    return sci(root.attr_double(key, object), 17);
  }
}

std::optional<double> parameter_double(const io::Group& root, const std::string& tool, const std::string& key) {
  const auto text = parameter(root, tool, key);
  if (!text) return std::nullopt;
  try {
    std::size_t used = 0;
    const double v = std::stod(*text, &used);
    if (used == text->size() || text->find_first_not_of(" \t", used) == std::string::npos) return v;
  } catch (const std::logic_error&) {
  }
  throw InputError(root.where("parameters/" + tool) + ": attribute '" + key + "' = '" + *text + "' is not a number");
}

// A body at a NaN position or angle would be left out of the picture unnoticed: InputError naming the dataset,
// the frame and the body.
void require_finite_frame(const io::Group& root, bool cells, const io::BodyFrame& f, long long frame) {
  const std::string group = cells ? "particles/cells/" : "particles/nodes/";
  const auto refuse = [&](const char* dataset, std::size_t i, const std::string& value) {
    throw InputError(root.where(group + dataset) + ": frame " + std::to_string(frame) + " (t = " + sci(f.time, 6) +
                     " s): " + (cells ? "cell " : "node ") + std::to_string(i) + ": " + value + " is not finite");
  };
  for (std::size_t i = 0; 2 * i + 1 < f.position.size(); ++i)
    if (!std::isfinite(f.position[2 * i]) || !std::isfinite(f.position[2 * i + 1]))
      refuse("position", i, "(" + sci(f.position[2 * i]) + ", " + sci(f.position[2 * i + 1]) + ")");
  for (std::size_t i = 0; i < f.angle.size(); ++i)
    if (!std::isfinite(f.angle[i])) refuse("angle", i, "angle " + sci(f.angle[i]));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::string pretty_unit(const std::string& unit) {
  if (unit == "m s-1") return "m/s";
  if (unit == "rad s-1") return "rad/s";
  return unit;
}

// A dataset or time series that colours the bodies, one value (or a 2-vector, drawn as its length) per body.
struct ColourField {
  std::string path, label;
  bool series = false;
  int components = 1;
  std::vector<double> values;  // a static dataset's
  io::SeriesInfo info;         // a series'
};

// Finds --colour's dataset or series (absolute, or under the bodies' group first) and checks its shape
// against the `n` bodies. UsageError naming what was tried or what does not fit.
ColourField find_colour_field(const io::Group& root, const std::string& colour, bool cells, bool run, std::size_t n) {
  ColourField field;
  const std::string body_group = cells ? "particles/cells" : "particles/nodes";
  std::vector<std::string> candidates;
  if (colour.front() == '/')
    candidates.push_back(colour.substr(1));
  else
    candidates = {body_group + "/" + colour, colour};
  for (const auto& c : candidates) {
    if (!root.has(c)) continue;
    field.path = c;
    break;
  }
  if (field.path.empty()) {
    std::string tried;
    for (const auto& c : candidates) tried += (tried.empty() ? "/" : " and /") + c;
    throw UsageError("--colour " + colour + ": " + root.file() + " has no dataset or time series " + tried +
                     " (or use fragment, speed, strain, none)");
  }
  const auto slash = field.path.rfind('/');
  const std::string parent = slash == std::string::npos ? "." : field.path.substr(0, slash);
  const std::string leaf = slash == std::string::npos ? field.path : field.path.substr(slash + 1);
  std::vector<hsize_t> dims;
  std::string unit;
  field.series = root.has(field.path + "/value");
  if (field.series) {
    if (!run) throw UsageError("--colour " + colour + ": a time series in a mesh file");
    field.info = parent == "." ? io::read_series_info(root, leaf) : io::read_series_info(root.group(parent), leaf);
    dims = field.info.frame_dims;
    if (root.has_attr("unit", field.path + "/value")) unit = root.attr_string("unit", field.path + "/value");
  } else {
    try {
      field.values = root.read<double>(field.path, &dims);
    } catch (const InputError&) {
      throw UsageError("--colour " + colour + ": " + root.where(field.path) +
                       " is neither a numeric dataset nor a time series (step, time, value)");
    }
    if (root.has_attr("unit", field.path)) unit = root.attr_string("unit", field.path);
  }
  const bool scalar = dims.size() == 1 && dims[0] == n;
  const bool vector = dims.size() == 2 && dims[0] == n && dims[1] == 2;
  if (!scalar && !vector) {
    std::string shape;
    for (auto d : dims) shape += (shape.empty() ? "" : "x") + std::to_string(d);
    throw UsageError("--colour " + colour + ": " + root.where(field.path) + " has " +
                     (field.series ? "frames of shape [" : "shape [") + shape + "], not one value (or two) per " +
                     (cells ? "cell" : "node") + " (" + std::to_string(n) + ")");
  }
  field.components = vector ? 2 : 1;
  field.label = (vector ? "|" + leaf + "|" : leaf) + (unit.empty() ? "" : " (" + pretty_unit(unit) + ")");
  return field;
}

// Cells coloured by fragment (single cells grey), and the legend: the 12 largest fragments of more than one
// cell and the number of single cells.
std::vector<Rgb> fragment_fill(const FragmentLabels& l, std::size_t n, Figure& fig) {
  std::vector<Rgb> fill(n, kPlainFill);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = l.cell_fragment[i];
    const bool single = id >= 0 && static_cast<std::size_t>(id) < l.cell_count.size() && l.cell_count[id] <= 1;
    fill[i] = single ? kDebrisGrey : category(id);
  }
  std::size_t shown = 0;
  for (std::size_t f = 0; f < l.mass.size() && shown < 12; ++f) {
    if (l.cell_count[f] <= 1) continue;
    fig.legend.push_back(
        {category(static_cast<std::int64_t>(f)),
         "#" + std::to_string(f) + "  " + sci(l.mass[f]) + " kg, " + std::to_string(l.cell_count[f]) + " cells"});
    ++shown;
  }
  std::size_t singles = 0;
  for (auto c : l.cell_count) singles += c <= 1 ? 1 : 0;
  if (singles) fig.legend.push_back({kDebrisGrey, std::to_string(singles) + " single cells"});
  fig.legend_title = std::to_string(l.mass.size()) + " fragments (frame " + std::to_string(l.frame) + ")";
  return fill;
}

// How the links of a frame are drawn.
struct LinkStyle {
  LinkMode mode = LinkMode::strain;
  bool run = false, cells = true;
  const std::optional<Threshold>* threshold = nullptr;
  double scale_max = 1.0;  // strain (or strain / threshold) at the ends of the colour scale
};

// Links: intact ones coloured by strain relative to the threshold, broken ones marked at their middle;
// the links' colour bar (merged with the bodies' when it is the same scale). Returns the broken links.
std::size_t add_links(Figure& fig, const std::vector<std::array<std::int64_t, 2>>& links,
                      const std::vector<double>& position, const std::vector<std::uint8_t>& intact,
                      const std::vector<double>& strain, const LinkStyle& style) {
  const std::optional<Threshold>& threshold = *style.threshold;
  auto at = [&](std::size_t i) { return Vec2(position[2 * i], position[2 * i + 1]); };
  std::size_t broken = 0;
  ColourScale scale;
  scale.palette = Palette::coolwarm;
  const double m = style.scale_max;
  scale.min = -m;
  scale.max = m;
  const double unit = threshold ? threshold->strain : 1.0;
  const std::string what = style.cells ? "beam" : "bond";
  scale.label = what + " strain" + (threshold ? " / threshold (" + threshold->label + ")" : " (1)");
  const bool colour_links = style.run && style.mode == LinkMode::strain;
  for (std::size_t b = 0; b < links.size(); ++b) {
    const auto i = static_cast<std::size_t>(links[b][0]), j = static_cast<std::size_t>(links[b][1]);
    const Vec2 a = at(i), c = at(j);
    if (!intact[b]) {
      fig.markers.push_back(0.5 * (a + c));
      ++broken;
    } else if (style.mode == LinkMode::strain) {
      fig.segments.push_back({a, c, colour_links ? scale(strain[b] / unit) : kPlainLink});
    }
  }
  if (colour_links) {
    const bool same = threshold && !fig.colour_bars.empty() && fig.colour_bars.back().palette == Palette::coolwarm &&
                      fig.colour_bars.back().min == scale.min && fig.colour_bars.back().max == scale.max;
    if (same)
      fig.colour_bars.back().label = "strain / threshold (" + threshold->label + ")";
    else
      fig.colour_bars.push_back(scale);
  }
  fig.marker_colour = style.mode == LinkMode::broken ? kBrokenMark : Rgb{0.05, 0.05, 0.05};
  return broken;
}

}  // namespace

LinkMode link_mode_from_text(const std::string& text, const std::string& option) {
  if (text == "strain" || text.empty()) return LinkMode::strain;
  if (text == "broken") return LinkMode::broken;
  if (text == "off") return LinkMode::off;
  throw UsageError(option + ": unknown mode '" + text + "' (strain, broken or off)");
}

FragmentLabels read_fragment_labels(const io::Group& fragments_root) {
  io::check_header(fragments_root, {"fragments"});
  return io::read_fragment_labels(fragments_root);
}

bool counted_from(const io::Group& fragments_root, const io::Group& run_root) {
  try {
    const io::FileProvenance run = io::read_provenance(run_root);
    const io::FileProvenance frags = io::read_provenance(fragments_root);
    if (run.file_uuid.empty()) return true;
    for (const auto& e : frags.history)
      if (e.file_uuid == run.file_uuid) return true;
    return false;
  } catch (const std::exception&) {
    return true;
  }
}

std::optional<Threshold> read_threshold(const io::Group& root, bool cells) {
  if (cells) {
    const auto t = parameter_double(root, "dem-run", "material.t_eps");
    if (!t || !(*t > 0.0)) return std::nullopt;
    return Threshold{*t, "t_ε = " + sci(*t)};
  }
  const auto cutoff = parameter(root, "rubber-run", "law.cutoff");
  if (cutoff && *cutoff == "none") return std::nullopt;
  const auto length = parameter_double(root, "rubber-run", "law.cutoff_length");
  if (!length || !root.has_attr("spacing", "particles/nodes")) return std::nullopt;
  const double spacing = root.attr_double("spacing", "particles/nodes");
  const double strain = *length / spacing - 1.0;
  if (!(strain > 0.0)) return std::nullopt;
  return Threshold{strain, "cut-off strain " + sci(strain)};
}

// One frame's state: positions (x0 y0 x1 y1 ...), angles (cells), velocities, link strains and flags.
struct RunPicture::FrameData {
  long long index = -1;  // -1: the reference state of a mesh file
  std::int64_t step = 0;
  double time = 0.0;
  std::vector<double> position, angle, velocity, strain;
  std::vector<std::uint8_t> intact;
};

RunPicture::RunPicture(const io::Group& root, std::optional<FragmentLabels> labels, PictureOptions options) try
    : root_(root), labels_(std::move(labels)), opt_(std::move(options)) {
  const std::string kind = io::check_header(root, {"mesh", "run"});
  run_ = kind == "run";
  cells_ = io::mesh_kind(root) == io::MeshKind::cells;
  if (cells_) {
    cell_mesh_ = io::read_cell_mesh(root);
    links_ = cell_mesh_.beam;
    link_length_ = median(cell_mesh_.beam_length);
    if (!(link_length_ > 0.0)) link_length_ = cell_mesh_.spacing;
  } else {
    node_mesh_ = io::read_node_mesh(root);
    links_ = node_mesh_.bond;
    link_length_ = median(node_mesh_.bond_length);
    if (!(link_length_ > 0.0)) link_length_ = node_mesh_.spacing;
  }
  if (run_) info_ = io::read_run_info(root);
  threshold_ = read_threshold(root, cells_);
  link_mode_ = link_mode_from_text(opt_.links);
  const std::size_t n = cells_ ? cell_mesh_.cells() : node_mesh_.nodes();

  if (labels_) {
    if (!cells_)
      throw UsageError("--fragments: " + root.file() + " is a rubber-lattice file; fragments label polygon cells");
    if (labels_->cell_fragment.size() != n)
      throw InputError(labels_->file + ":/fragments/cell_fragment: labels " +
                       std::to_string(labels_->cell_fragment.size()) + " cells, but " + root.file() + " has " +
                       std::to_string(n) + " (fragments of another run?)");
  }

  colour_ = opt_.colour;
  if (colour_.empty()) colour_ = labels_ ? "fragment" : !run_ ? "none" : cells_ ? "speed" : "strain";
  if (colour_ == "fragment") {
    if (!labels_) throw UsageError("--colour fragment: give the fragments file with --fragments FRAGS.h5");
  } else if (colour_ == "speed") {
    if (!run_) throw UsageError("--colour speed: " + root.file() + " is a mesh: it has no velocities");
  } else if (colour_ == "strain") {
    if (!run_) throw UsageError("--colour strain: " + root.file() + " is a mesh: it has no strains");
  } else if (colour_ != "none") {
    ColourField field = find_colour_field(root, colour_, cells_, run_, n);
    field_path_ = std::move(field.path);
    field_label_ = std::move(field.label);
    field_series_ = field.series;
    field_components_ = field.components;
    field_static_ = std::move(field.values);
    field_info_ = std::move(field.info);
  }
  if (opt_.range) fixed_range_ = opt_.range;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the picture of " + root.file());
}

long long RunPicture::default_frame() const {
  if (!run_) return 0;
  if (labels_ && labels_->frame >= 0 && static_cast<std::size_t>(labels_->frame) < frames()) return labels_->frame;
  return static_cast<long long>(frames()) - 1;
}

long long RunPicture::frame_index(long long frame) const {
  if (!run_) return 0;
  const auto count = static_cast<long long>(frames());
  const long long k = frame < 0 ? count + frame : frame;
  if (k < 0 || k >= count)
    throw UsageError("--frame " + std::to_string(frame) + ": " + root_.file() + " has frames 0.." +
                     std::to_string(count - 1) + " (negative counts from the end)");
  return k;
}

long long RunPicture::frame_at_time(double t) const {
  if (!run_) return 0;
  return io::frame_at_time(info_, t);
}

RunPicture::FrameData RunPicture::load(long long frame) const {
  FrameData d;
  if (!run_) {
    if (cells_) {
      for (const auto& c : cell_mesh_.centroid) d.position.insert(d.position.end(), {c.x(), c.y()});
      d.angle.assign(cell_mesh_.cells(), 0.0);
      d.intact.assign(cell_mesh_.beams(), 1);
    } else {
      for (const auto& p : node_mesh_.position) d.position.insert(d.position.end(), {p.x(), p.y()});
      d.intact = node_mesh_.intact;
    }
    d.strain.assign(links_.size(), 0.0);
    return d;
  }
  const long long k = frame_index(frame);
  io::BodyFrame f = io::read_frame(root_, k);
  require_finite_frame(root_, cells_, f, k);
  const std::size_t n = info_.mass.size();
  if (cells_ && n != cell_mesh_.cells())
    throw InputError(root_.where("particles/cells/mass") + ": " + std::to_string(n) + " cells, the mesh has " +
                     std::to_string(cell_mesh_.cells()));
  if (!cells_ && n != node_mesh_.nodes())
    throw InputError(root_.where("particles/nodes/mass") + ": " + std::to_string(n) + " nodes, the mesh has " +
                     std::to_string(node_mesh_.nodes()));
  if (f.intact.size() != links_.size() || f.strain.size() != links_.size())
    throw InputError(root_.where(cells_ ? "connectivity/beams/trajectory" : "connectivity/bonds/trajectory") +
                     ": frames of " + std::to_string(f.intact.size()) + " links, the mesh has " +
                     std::to_string(links_.size()));
  d.index = k;
  d.step = f.step;
  d.time = f.time;
  d.position = std::move(f.position);
  d.angle = std::move(f.angle);
  d.velocity = std::move(f.velocity);
  d.strain = std::move(f.strain);
  d.intact = std::move(f.intact);
  return d;
}

// The bodies' field for this frame: one value per body (NaN where undefined).
std::vector<double> RunPicture::body_values(const FrameData& d) const {
  const std::size_t n = d.position.size() / 2;
  std::vector<double> v;
  if (colour_ == "speed") {
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = std::hypot(d.velocity[2 * i], d.velocity[2 * i + 1]);
  } else if (colour_ == "strain") {
    std::vector<double> sum(n, 0.0), count(n, 0.0);
    for (std::size_t b = 0; b < links_.size(); ++b) {
      if (!d.intact[b]) continue;
      for (auto i : links_[b]) {
        sum[static_cast<std::size_t>(i)] += d.strain[b];
        count[static_cast<std::size_t>(i)] += 1.0;
      }
    }
    v.resize(n);
    const double unit = threshold_ ? threshold_->strain : 1.0;
    for (std::size_t i = 0; i < n; ++i) v[i] = count[i] > 0 ? sum[i] / count[i] / unit : kNaN;
  } else if (!field_path_.empty()) {
    std::vector<double> raw;
    if (field_series_) {
      // The series frame nearest in time to the trajectory frame (the same index when they share steps).
      std::size_t best = 0;
      for (std::size_t k = 0; k < field_info_.time.size(); ++k)
        if (std::abs(field_info_.time[k] - d.time) < std::abs(field_info_.time[best] - d.time)) best = k;
      const auto slash = field_path_.rfind('/');
      const auto k = static_cast<long long>(best);
      raw = slash == std::string::npos ? io::read_series_frame<double>(root_, field_path_, k)
                                       : io::read_series_frame<double>(root_.group(field_path_.substr(0, slash)),
                                                                       field_path_.substr(slash + 1), k);
    } else {
      raw = field_static_;
    }
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = field_components_ == 2 ? std::hypot(raw[2 * i], raw[2 * i + 1]) : raw[i];
  }
  return v;
}

std::array<double, 2> RunPicture::auto_range(const std::vector<double>& v) const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double x : v)
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  if (!(hi >= lo)) return {0.0, 1.0};
  if (colour_ == "speed") lo = 0.0;
  if (colour_ == "strain") {
    if (threshold_) return {-1.0, 1.0};
    const double m = std::max(std::abs(lo), std::abs(hi));
    return {-m, m};
  }
  return {lo, hi};
}

double RunPicture::link_scale_max(const FrameData& d) const {
  if (threshold_) return threshold_->strain;
  double m = 0.0;
  for (std::size_t b = 0; b < links_.size(); ++b)
    if (d.intact[b] && std::isfinite(d.strain[b])) m = std::max(m, std::abs(d.strain[b]));
  return m > 0.0 ? m : 1.0;
}

Figure RunPicture::figure(long long frame) const try {
  const FrameData d = load(frame);
  const std::size_t n = d.position.size() / 2;
  auto at = [&](std::size_t i) { return Vec2(d.position[2 * i], d.position[2 * i + 1]); };
  Figure fig;
  fig.link_length = link_length_;

  // The bodies' colours.
  std::vector<Rgb> fill(n, kPlainFill);
  if (colour_ == "fragment") {
    fill = fragment_fill(*labels_, n, fig);
  } else if (colour_ != "none") {
    const auto v = body_values(d);
    ColourScale scale;
    const auto r = fixed_range_ ? *fixed_range_ : auto_range(v);
    scale.min = r[0];
    scale.max = r[1];
    if (colour_ == "speed") {
      scale.label = "speed (m/s)";
    } else if (colour_ == "strain") {
      scale.palette = Palette::coolwarm;
      scale.label = std::string("mean ") + (cells_ ? "beam" : "bond") + " strain" +
                    (threshold_ ? " / threshold (" + threshold_->label + ")" : " (1)");
    } else {
      scale.label = field_label_;
    }
    for (std::size_t i = 0; i < n; ++i) fill[i] = std::isfinite(v[i]) ? scale(v[i]) : kDebrisGrey;
    fig.colour_bars.push_back(scale);
  }

  if (cells_) {
    fig.polygons.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      fig.polygons.push_back({world_polygon(cell_mesh_.polygon(i), at(i), d.angle[i]), fill[i]});
  } else {
    fig.dot_radius = 0.3 * link_length_;
    fig.dots.reserve(n);
    for (std::size_t i = 0; i < n; ++i) fig.dots.push_back({at(i), fill[i]});
  }

  std::size_t broken = 0;
  if (link_mode_ != LinkMode::off) {
    const double m = threshold_ ? 1.0 : fixed_link_max_ ? *fixed_link_max_ : link_scale_max(d);
    broken = add_links(fig, links_, d.position, d.intact, d.strain, {link_mode_, run_, cells_, &threshold_, m});
  }

  if (opt_.title) {
    std::string name = opt_.name.empty() ? std::filesystem::path(root_.file()).filename().string() : opt_.name;
    std::string t = name;
    if (run_) {
      t += "   frame " + std::to_string(d.index) + "/" + std::to_string(frames() - 1) + "   t = " + sci(d.time, 4) +
           " s";
    } else {
      t += "   mesh: " + std::to_string(n) + (cells_ ? " cells, " : " nodes, ") + std::to_string(links_.size()) +
           (cells_ ? " beams" : " bonds");
    }
    if (link_mode_ != LinkMode::off && broken)
      t += "   × " + std::to_string(broken) + (run_ ? " broken " : " cut ") + (cells_ ? "beams" : "bonds");
    fig.title = t;
  }
  fig.axes = opt_.axes;
  fig.view = opt_.view ? *opt_.view : content_bounds(fig);
  return fig;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the picture of frame " + std::to_string(frame));
}

void RunPicture::fix_across(const std::vector<long long>& frames) {
  std::optional<std::array<double, 4>> view;
  std::optional<std::array<double, 2>> range;
  double link_max = 0.0;
  for (long long k : frames) {
    const Figure f = figure(k);
    view = view ? merge_bounds(*view, f.view) : f.view;
    if (!fixed_range_ && colour_ != "fragment" && colour_ != "none" && !f.colour_bars.empty()) {
      const auto& bar = f.colour_bars.front();
      range = range ? std::array<double, 2>{std::min((*range)[0], bar.min), std::max((*range)[1], bar.max)}
                    : std::array<double, 2>{bar.min, bar.max};
    }
    if (!threshold_ && link_mode_ == LinkMode::strain && run_) link_max = std::max(link_max, link_scale_max(load(k)));
  }
  if (!opt_.view && view) opt_.view = view;
  if (range) fixed_range_ = range;
  if (link_max > 0.0) fixed_link_max_ = link_max;
}

}  // namespace frac::render
