#pragma once
// The datasets a rubber run can write in every frame (run/engine's FrameDataset), as rows of a table that a
// scene names by key (output.frames, all of them by default): a new per-frame dataset is one row.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dynamics/integrator.hpp"
#include "rubber/model.hpp"

namespace frac::rubber {

struct FrameRow {
  std::string name, group, unit;
  bool per_bond = false;  // one value (row) a bond of the mesh, else a node
  std::size_t components = 1;
  bool flags = false;     // bytes (fill_flags), else numbers (fill)
  std::function<void(const Model&, const dynamics::Integrator&, std::span<double>)> fill;
  std::function<void(const Model&, const dynamics::Integrator&, std::span<std::uint8_t>)> fill_flags;
};

// The schema's trajectory (docs/SCHEMA.md): position, velocity, intact, strain.
const std::vector<FrameRow>& frame_table();
std::vector<std::string> frame_names();

}  // namespace frac::rubber
