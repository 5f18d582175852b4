#pragma once
// What an engine (the polygon DEM, the rubber lattice) gives the run driver (run/driver): its step as phases
// (core/phases), its state as a registry (core/state_registry), its observables and per-frame datasets as
// tables, its stop rule and its output schedule. The driver writes, checkpoints and stops; an engine includes
// no writer.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/phases.hpp"
#include "core/state_registry.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/cell_mesh.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::run {

// An observable: a value of the state at an observation, named, with its unit (the run file's
// /observables/<name>).
struct Observable {
  std::string name, unit;
  std::function<double()> value;
};

// A dataset of every frame (a time series of the run file): `group`/`name`, `items` rows of `components` values
// (1: one value an item), numbers or flags (bytes); fill writes the current state's values.
struct FrameDataset {
  std::string group, name, unit;
  std::size_t items = 0, components = 1;
  bool flags = false;
  std::function<void(std::span<double>)> fill;
  std::function<void(std::span<std::uint8_t>)> fill_flags;
};

// A beam or bond that broke in a step: its index in the mesh, and how (1 stretching, 2 bending).
struct Event {
  std::int64_t index;
  std::uint8_t mode;
};

// The mesh a run starts from and its per-body constants (the run file's static part): cells with mass and
// moment of inertia, or nodes with mass.
struct RunBodies {
  const mesh::CellMesh* cells = nullptr;
  const mesh::NodeMesh* nodes = nullptr;
  std::vector<double> mass, inertia;
};

class Engine {
 public:
  virtual ~Engine() = default;
  // The integrator started from the initial state (its first force evaluation).
  virtual void start() = 0;
  virtual const dynamics::Integrator& integrator() const = 0;
  // One step: its phases, run on a team of team_size() threads after bind_step (serial, before each run).
  virtual Phases step_phases() = 0;
  virtual void bind_step() = 0;
  virtual std::size_t team_size() const = 0;
  // After a step, serially: its bookkeeping and checks (RuntimeError naming the step for a non-finite value),
  // and the beams or bonds that broke in it, appended to `events`.
  virtual void after_step(std::int64_t step, std::vector<Event>& events) = 0;
  // Why the run stops at `step` (after its observation and frame), "" while it goes on.
  virtual std::string stop_reason(std::int64_t step) const = 0;
  // The output schedule: a frame at the time of the step just taken (then frame_written), an observation at
  // `step` (`frame`: one is due).
  virtual bool frame_due() const = 0;
  virtual void frame_written() = 0;
  virtual bool observe_due(std::int64_t step, bool frame) const = 0;
  // An observation: measure (its checks and the values the observables read), then the table's rows.
  virtual void measure(std::int64_t step) = 0;
  virtual const std::vector<Observable>& observables() const = 0;
  virtual const std::vector<FrameDataset>& frame_datasets() const = 0;
  virtual RunBodies bodies() const = 0;
  // The state a continuation needs besides the driver's own (core/state_registry), declared by start().
  virtual const StateRegistry& state() const = 0;
  // Attributes of the run file's root beside the driver's (steps, end_time, stop_reason).
  virtual std::vector<std::pair<std::string, std::int64_t>> run_attributes() const { return {}; }
  // The progress line at `step`: the loop started at `first_step` (time `first_t`) `elapsed` s ago.
  virtual std::string progress_line(std::int64_t step, std::int64_t first_step, double first_t,
                                    double elapsed) const = 0;
};

}  // namespace frac::run
