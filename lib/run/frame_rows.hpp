#pragma once
// The per-frame datasets an engine can write, as rows of a table that a scene names by key (output.frames): a
// new dataset is one row. An engine turns the rows a scene chose into the driver's FrameDatasets (run/engine).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dynamics/integrator.hpp"
#include "run/engine.hpp"

namespace frac::run {

template <class System>
struct FrameRow {
  std::string name, group, unit;
  bool per_link = false;  // one value (row) a beam or bond of the mesh, else a body (cell, node)
  std::size_t components = 1;
  bool flags = false;  // bytes (fill_flags), else numbers (fill)
  std::function<void(const System&, const dynamics::Integrator&, std::span<double>)> fill;
  std::function<void(const System&, const dynamics::Integrator&, std::span<std::uint8_t>)> fill_flags;
};

// x and y of each of n bodies, interleaved, from coordinates laid out as blocks (x of every body, then y, ...).
inline void interleave_xy(std::span<const double> s, std::size_t n, std::span<double> out) {
  for (std::size_t k = 0; k < n; ++k) {
    out[2 * k] = s[k];
    out[2 * k + 1] = s[n + k];
  }
}

template <class System>
std::vector<std::string> row_names(const std::vector<FrameRow<System>>& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.push_back(row.name);
  return names;
}

// The rows of `table` named in `chosen`, in the table's order, as datasets of `system` (`bodies` and `links` long)
// filled from the integrator's state.
template <class System>
std::vector<FrameDataset> frame_datasets(const std::vector<FrameRow<System>>& table,
                                         const std::vector<std::string>& chosen, const System& system,
                                         const dynamics::Integrator& integrator, std::size_t bodies,
                                         std::size_t links) {
  std::vector<FrameDataset> out;
  for (const auto& row : table) {
    if (std::find(chosen.begin(), chosen.end(), row.name) == chosen.end()) continue;
    FrameDataset d{row.group, row.name, row.unit, row.per_link ? links : bodies, row.components, row.flags, {}, {}};
    const System* s = &system;
    const dynamics::Integrator* in = &integrator;
    if (row.flags)
      d.fill_flags = [s, in, &row](std::span<std::uint8_t> v) { row.fill_flags(*s, *in, v); };
    else
      d.fill = [s, in, &row](std::span<double> v) { row.fill(*s, *in, v); };
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace frac::run
