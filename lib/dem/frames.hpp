#pragma once
// The datasets a DEM run can write in every frame (run/engine's FrameDataset), as rows of a table that a scene
// names by key (output.frames, all of them by default): a new per-frame dataset is one row.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dem/model.hpp"
#include "dynamics/integrator.hpp"

namespace frac::dem {

struct FrameRow {
  std::string name, group, unit;
  bool per_beam = false;  // one value (row) a beam, else a cell
  std::size_t components = 1;
  bool flags = false;     // bytes (fill_flags), else numbers (fill)
  std::function<void(const Model&, const dynamics::Integrator&, std::span<double>)> fill;
  std::function<void(const Model&, const dynamics::Integrator&, std::span<std::uint8_t>)> fill_flags;
};

// The schema's trajectory (docs/SCHEMA.md): position, velocity, angle, angular_velocity, intact, strain.
const std::vector<FrameRow>& frame_table();
std::vector<std::string> frame_names();

}  // namespace frac::dem
