#include "rubber/failures.hpp"

namespace frac::rubber {

void settle_failures(ForceContext& c, std::size_t i0, std::size_t i1) {
  for (std::size_t b = 3 * i0; b < 3 * i1; ++b)
    if (c.status[b] == kFreezing) c.status[b] = kBroken;
}

}  // namespace frac::rubber
