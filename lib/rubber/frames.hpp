#pragma once
// The datasets a rubber run can write in every frame (run/engine's FrameDataset), as rows of a table that a
// scene names by key (output.frames, all of them by default): a new per-frame dataset is one row.
#include <string>
#include <vector>

#include "dynamics/integrator.hpp"
#include "rubber/model.hpp"
#include "run/frame_rows.hpp"

namespace frac::rubber {

using FrameRow = run::FrameRow<Model>;

// The schema's trajectory (docs/SCHEMA.md): position, velocity, intact, strain.
const std::vector<FrameRow>& frame_table();
inline std::vector<std::string> frame_names() { return run::row_names(frame_table()); }

}  // namespace frac::rubber
