#include "rubber/frames.hpp"

namespace frac::rubber {
const std::vector<FrameRow>& frame_table() {
  using In = const dynamics::Integrator&;
  const std::string nodes = "particles/nodes", bonds = "connectivity/bonds/trajectory";
  static const std::vector<FrameRow> table{
      {"position",
       nodes,
       "m",
       false,
       2,
       false,
       [](const Model& m, In in, std::span<double> out) { run::interleave_xy(in.q(), m.nodes(), out); },
       {}},
      {"velocity",
       nodes,
       "m s-1",
       false,
       2,
       false,
       [](const Model& m, In in, std::span<double> out) { run::interleave_xy(in.v(), m.nodes(), out); },
       {}},
      {"intact",
       bonds,
       "",
       true,
       1,
       true,
       {},
       [](const Model& m, In in, std::span<std::uint8_t> out) {
         const Lattice& L = m.lattice();
         for (std::size_t k = 0; k < out.size(); ++k)
           out[k] = m.holds(static_cast<std::size_t>(L.bond_id[k]), in.q()) ? 1 : 0;
       }},
      {"strain",
       bonds,
       "1",
       true,
       1,
       false,
       [](const Model& m, In in, std::span<double> out) {
         const Lattice& L = m.lattice();
         for (std::size_t k = 0; k < out.size(); ++k)
           out[k] = m.bond_length(static_cast<std::size_t>(L.bond_id[k]), in.q()) / L.spacing - 1;
       },
       {}},
  };
  return table;
}

}  // namespace frac::rubber
