#pragma once
// Pictures of mesh and run files (docs/render.md): builds the Figure of any frame of a polygon-DEM run
// (cells as polygons: body-frame vertices turned by the frame's angle about the frame's centroid),
// of a rubber run (nodes as dots) or of a mesh (the reference state), with beams or bonds coloured by
// strain relative to the breaking threshold and broken ones marked.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/fragment_labels.hpp"
#include "io/hdf5.hpp"
#include "io/run_io.hpp"
#include "mesh/cell_mesh.hpp"
#include "mesh/node_mesh.hpp"
#include "render/figure.hpp"

namespace frac::render {

enum class LinkMode { strain, broken, off };
// "strain", "broken" or "off"; UsageError naming `option` otherwise.
LinkMode link_mode_from_text(const std::string& text, const std::string& option = "--beams");

struct PictureOptions {
  // What colours the cells or nodes: "fragment" (needs fragments), "speed", "strain" (mean strain of the
  // intact beams or bonds at each body), "none", or a dataset or time series of the file with one value
  // (or a 2-vector, drawn as its length) per body: "particles/cells/angle", "/particles/cells/area",
  // "angular_velocity" (looked up under the bodies' group first). "" picks the file's default.
  std::string colour;
  std::string links;                           // "strain" | "broken" | "off"; "" = strain
  std::optional<std::array<double, 2>> range;  // colour range of the bodies' field (fixes auto ranges)
  std::optional<std::array<double, 4>> view;   // m: xmin, ymin, xmax, ymax
  bool axes = false;
  bool title = true;
  std::string name;  // how the title names the file ("" = its path)
};

// Labels from a fragments file (kind "fragments"): fragment of each cell, fragments sorted by mass.
using io::FragmentLabels;
// Checks the header and reads /fragments' labels (io/fragment_labels).
FragmentLabels read_fragment_labels(const io::Group& fragments_root);

// Whether a fragments file was counted from this run: its provenance history names the run file's
// uuid. True when either file carries no readable provenance (nothing to tell).
bool counted_from(const io::Group& fragments_root, const io::Group& run_root);

// The breaking threshold beams and bonds are coloured against: DEM, /parameters/dem-run attribute
// "material.t_eps"; rubber, the strain at the bond cut-off, law.cutoff_length / spacing - 1 (none when
// law.cutoff = none). nullopt when the file does not say.
struct Threshold {
  double strain = 0.0;
  std::string label;  // "t_ε = 0.03"
};
std::optional<Threshold> read_threshold(const io::Group& root, bool cells);

class RunPicture {
 public:
  // `root`: a mesh or run file (checked); it must outlive this object. `labels`: for --colour fragment.
  RunPicture(const io::Group& root, std::optional<FragmentLabels> labels, PictureOptions options);

  bool is_run() const { return run_; }
  bool cells() const { return cells_; }
  std::size_t frames() const { return run_ ? info_.step.size() : 0; }
  const io::RunInfo& info() const { return info_; }
  // The frame drawn when none is asked for: the fragments' frame, else the final state.
  long long default_frame() const;
  // Index (0..frames-1) of a frame given as an index (negative from the end) or nearest to a time.
  long long frame_index(long long frame) const;  // UsageError naming --frame when out of range
  long long frame_at_time(double t) const;
  const std::string& colour() const { return colour_; }
  const std::optional<FragmentLabels>& labels() const { return labels_; }

  // The picture of frame `frame` (an index; ignored for mesh files).
  Figure figure(long long frame) const;
  // For a sequence: fixes the view and the automatic colour ranges to cover all these frames.
  void fix_across(const std::vector<long long>& frames);

 private:
  struct Field;
  struct FrameData;
  FrameData load(long long frame) const;
  std::vector<double> body_values(const FrameData& d) const;
  std::array<double, 2> auto_range(const std::vector<double>& v) const;
  double link_scale_max(const FrameData& d) const;

  const io::Group& root_;
  bool run_ = false, cells_ = true;
  io::RunInfo info_;
  mesh::CellMesh cell_mesh_;
  mesh::NodeMesh node_mesh_;
  std::vector<std::array<std::int64_t, 2>> links_;
  double link_length_ = 0.0;
  std::optional<Threshold> threshold_;
  std::optional<FragmentLabels> labels_;
  PictureOptions opt_;
  std::string colour_;  // resolved
  LinkMode link_mode_ = LinkMode::strain;
  // A dataset field: path of the dataset or series group, series or static, components.
  std::string field_path_, field_label_;
  bool field_series_ = false;
  int field_components_ = 1;
  std::vector<double> field_static_;
  io::SeriesInfo field_info_;
  std::optional<std::array<double, 2>> fixed_range_;  // from options or fix_across
  std::optional<double> fixed_link_max_;              // link strain range without a threshold
};

}  // namespace frac::render
