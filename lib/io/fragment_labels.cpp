#include "io/fragment_labels.hpp"

#include <string>

#include "core/error.hpp"

namespace frac::io {

FragmentLabels read_fragment_labels(const Group& root) {
  FragmentLabels l;
  const Group g = root.group("fragments");
  l.file = root.file();
  l.frame = g.attr_int("frame");
  l.step = g.attr_int("step");
  l.time = g.attr_double("time");
  l.cell_fragment = g.read<std::int64_t>("cell_fragment", nullptr, 1);
  l.mass = g.read<double>("mass", nullptr, 1);
  const std::size_t nf = l.mass.size();
  if (g.attr_int("fragments") != static_cast<std::int64_t>(nf))
    throw InputError(g.where() + ": attribute 'fragments' (" + std::to_string(g.attr_int("fragments")) +
                     ") does not match the length of mass (" + std::to_string(nf) + ")");
  l.cell_count = g.read<std::int64_t>("cell_count", nullptr, 1);
  if (l.cell_count.size() != nf)
    throw InputError(g.where("cell_count") + ": has " + std::to_string(l.cell_count.size()) + " values, expected " +
                     std::to_string(nf) + " (one per fragment)");
  std::vector<std::int64_t> counted(nf, 0);
  for (std::size_t i = 0; i < l.cell_fragment.size(); ++i) {
    const auto id = l.cell_fragment[i];
    if (id < 0 || static_cast<std::size_t>(id) >= nf)
      throw InputError(g.where("cell_fragment") + ": cell " + std::to_string(i) + " has fragment " +
                       std::to_string(id) + ", outside 0.." + std::to_string(static_cast<long long>(nf) - 1));
    ++counted[static_cast<std::size_t>(id)];
  }
  if (counted != l.cell_count)
    throw InputError(g.where("cell_count") + ": does not match the cells labelled in cell_fragment");
  return l;
}

}  // namespace frac::io
