#pragma once
// The run part of the file layout (docs/SCHEMA.md, "Run files"): a run file (root kind "run", root
// attribute model = "dem" | "rubber") holds the mesh it started from (io/mesh_io), the static per-body
// data (mass, moment of inertia), decimated trajectory frames as H5MD time series, the observables
// and the beam-break events. The last frame of every trajectory is always the final state.
//
//   DEM:    /particles/cells/{mass [N] kg, inertia [N] kg m^2}
//           /particles/cells/{position [T,N,2] m, angle [T,N] rad, velocity [T,N,2] m/s,
//                             angular_velocity [T,N] rad/s}          each {step, time, value}
//           /connectivity/beams/trajectory/{intact [T,B] uint8, strain [T,B] 1}  each {step, time, value}
//   rubber: /particles/nodes/mass [N] kg
//           /particles/nodes/{position [T,N,2] m, velocity [T,N,2] m/s}
//           /connectivity/bonds/trajectory/{intact [T,B] uint8, strain [T,B] 1}
//   both:   /observables/<name>/{step, time, value}, /observables/beam_breaks (or bond_breaks):
//           step [K], time [K], index [K], mode [K] (1 stretching dominated, 2 bending dominated; rubber: 1)
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "io/hdf5.hpp"
#include "io/series.hpp"
#include "mesh/cell_mesh.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::io {

// One frame of a body trajectory: positions and velocities interleaved (x0, y0, x1, y1, ...);
// angle and angular_velocity empty for the rubber lattice.
struct BodyFrame {
  std::int64_t step = 0;
  double time = 0;
  std::vector<double> position, velocity, angle, angular_velocity;
  std::vector<std::uint8_t> intact;  // per beam or bond
  std::vector<double> strain;        // per beam or bond: (l - l0)/l0
};

struct BreakEvent {
  std::int64_t step;
  double time;
  std::int64_t index;  // beam or bond
  std::uint8_t mode;   // 1 stretching dominated, 2 bending dominated
};

// A trajectory series of a run file: `group`/`name` (the group under the root, its missing parents created),
// frames of shape `dims`, of numbers or of flags (uint8).
struct SeriesSpec {
  std::string group, name;
  std::vector<hsize_t> dims;
  std::string unit;
  bool flags = false;
};
// The trajectory of the schema (above): position, velocity, (angle, angular_velocity,) intact, strain.
std::vector<SeriesSpec> standard_trajectory(bool cells, std::size_t bodies, std::size_t links);

class RunWriter {
 public:
  // Writes the mesh and the static per-body data under `root` (header written by the caller).
  RunWriter(Group& root, const mesh::CellMesh& mesh, std::span<const double> mass, std::span<const double> inertia);
  RunWriter(Group& root, const mesh::NodeMesh& mesh, std::span<const double> mass);

  // The trajectory's series, in the order they are created at the first frame (the schema's by default); before
  // the first frame or a replay.
  void declare_trajectory(std::vector<SeriesSpec> specs);
  bool trajectory_started() const { return !series_.empty(); }
  // Appends a frame to series k of the trajectory (values of its shape).
  void append(std::size_t k, std::int64_t step, double time, std::span<const double> values);
  void append(std::size_t k, std::int64_t step, double time, std::span<const std::uint8_t> values);
  // Appends one frame of the schema's trajectory (sizes checked against the mesh).
  void write_frame(const BodyFrame& frame);
  // Appends a scalar (or fixed-size vector) observable; the series is created at its first value.
  void observe(const std::string& name, std::int64_t step, double time, std::span<const double> value,
               std::string_view unit);
  void observe(const std::string& name, std::int64_t step, double time, double value, std::string_view unit) {
    observe(name, step, time, std::span<const double>(&value, 1), unit);
  }
  void record_break(const BreakEvent& e) { breaks_.push_back(e); }
  // Writes what the series still buffer and the break events; call once at the end.
  void finish();
  // Writes what the series buffer.
  void flush();
  // A checkpoint's copy of the output so far (io/checkpoint): every series, the list of the observables' names
  // and the break events, under `to` at their paths in the run file.
  void copy_progress(Group& to);
  // Continues from such a copy: its frames, observables and break events appended, as if this writer had
  // written them. InputError if they do not fit this run.
  void replay(const Group& from);
  std::size_t frames() const { return series_.empty() ? 0 : series_.front()->frames(); }

 private:
  void create_trajectory();  // the declared series (at the first frame)
  SeriesWriter& observable(const std::string& name, std::vector<hsize_t> dims, std::string_view unit);
  void write_breaks(Group& root) const;
  Group& root_;  // outlives the writer (an OutputFile's root)
  bool cells_;
  std::size_t bodies_, links_;
  std::vector<SeriesSpec> specs_;
  std::vector<std::unique_ptr<SeriesWriter>> series_;  // one for each of specs_ from the first frame on
  std::map<std::string, std::unique_ptr<SeriesWriter>> observables_;
  std::vector<BreakEvent> breaks_;
};

// What a reader of a run file needs: the model, the static body data and the frame list.
struct RunInfo {
  std::string model;                  // "dem" or "rubber"
  std::vector<double> mass, inertia;  // inertia empty for rubber
  std::vector<std::int64_t> step;     // of the trajectory frames
  std::vector<double> time;
};
// InputError naming the file when it is not a run file.
RunInfo read_run_info(const Group& root);
// One frame; negative counts from the end (-1 = final state).
BodyFrame read_frame(const Group& root, long long frame);
// The frame whose time is closest to t.
long long frame_at_time(const RunInfo& info, double t);
std::vector<BreakEvent> read_breaks(const Group& root);

}  // namespace frac::io
