#pragma once
// The cells' fragment labels of a fragments file (docs/fragments.md: /fragments cell_fragment, mass,
// cell_count and the frame they were counted at): what a picture colours cells by, and the first part of
// what analysis/fragments_io reads back. Plain arrays: io knows no analysis type.
#include <cstdint>
#include <string>
#include <vector>

#include "io/hdf5.hpp"

namespace frac::io {

struct FragmentLabels {
  std::vector<std::int64_t> cell_fragment;  // fragment of each cell
  std::vector<double> mass;                 // kg, per fragment
  std::vector<std::int64_t> cell_count;     // per fragment
  std::int64_t frame = -1;                  // the run frame they were counted at
  std::int64_t step = 0;
  double time = 0.0;
  std::string file;
};

// Reads the labels of /fragments; InputError naming the dataset when the lengths disagree, a label is outside
// the fragments or the cell counts do not match the labels.
FragmentLabels read_fragment_labels(const Group& root);

}  // namespace frac::io
