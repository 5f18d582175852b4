#include "dem/frames.hpp"

#include <algorithm>

namespace frac::dem {
namespace {

// The third block: the angles, or their rates.
void turns(std::span<const double> s, std::size_t n, std::span<double> out) {
  std::copy(s.begin() + static_cast<std::ptrdiff_t>(2 * n), s.begin() + static_cast<std::ptrdiff_t>(3 * n),
            out.begin());
}

}  // namespace

const std::vector<FrameRow>& frame_table() {
  using In = const dynamics::Integrator&;
  const std::string cells = "particles/cells", beams = "connectivity/beams/trajectory";
  static const std::vector<FrameRow> table{
      {"position",
       cells,
       "m",
       false,
       2,
       false,
       [](const Model& m, In in, std::span<double> out) { run::interleave_xy(in.q(), m.bodies().n, out); },
       {}},
      {"velocity",
       cells,
       "m s-1",
       false,
       2,
       false,
       [](const Model& m, In in, std::span<double> out) { run::interleave_xy(in.v(), m.bodies().n, out); },
       {}},
      {"angle",
       cells,
       "rad",
       false,
       1,
       false,
       [](const Model& m, In in, std::span<double> out) { turns(in.q(), m.bodies().n, out); },
       {}},
      {"angular_velocity",
       cells,
       "rad s-1",
       false,
       1,
       false,
       [](const Model& m, In in, std::span<double> out) { turns(in.v(), m.bodies().n, out); },
       {}},
      {"intact",
       beams,
       "",
       true,
       1,
       true,
       {},
       [](const Model& m, In, std::span<std::uint8_t> out) {
         const auto intact = m.beams().intact();
         std::copy(intact.begin(), intact.end(), out.begin());
       }},
      {"strain",
       beams,
       "1",
       true,
       1,
       false,
       [](const Model& m, In in, std::span<double> out) { m.beams().strains(in.q(), out); },
       {}},
  };
  return table;
}

}  // namespace frac::dem
