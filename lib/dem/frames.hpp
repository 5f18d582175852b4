#pragma once
// The datasets a DEM run can write in every frame (run/engine's FrameDataset), as rows of a table that a scene
// names by key (output.frames, all of them by default): a new per-frame dataset is one row.
#include <string>
#include <vector>

#include "dem/model.hpp"
#include "dynamics/integrator.hpp"
#include "run/frame_rows.hpp"

namespace frac::dem {

using FrameRow = run::FrameRow<Model>;

// The schema's trajectory (docs/SCHEMA.md): position, velocity, angle, angular_velocity, intact, strain.
const std::vector<FrameRow>& frame_table();
inline std::vector<std::string> frame_names() { return run::row_names(frame_table()); }

}  // namespace frac::dem
