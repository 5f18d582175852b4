#pragma once
// Bond failure, decided at the positions a step ends at, before any force there is used: a bond past its cut-off
// u_c is recorded once (an event) and fails past u_c + break_extra, or at u_c itself under energy-neutral failure,
// where it becomes kFreezing: the centres of its ends freeze its three-body terms in this evaluation, and
// settle_failures makes it kBroken after it. Verlet's step ends with the evaluation at its final positions (the
// closing half-kick needs it), so this is the lattice's "break after the step", as the DEM's beams break after
// its corrector. The decision is taken in the bonds pass, where the bond's length is computed anyway: a pass of
// its own over the bonds cost 5-8 % of the step at 10^6 nodes.
#include <cstddef>

#include "rubber/forces.hpp"

namespace frac::rubber {

// Bond b of a tracked evaluation (c.track), at length u > its cut-off u_c: records its first passage (events) and
// whether it fails now, setting its status (kFreezing with c.freeze, else kBroken) and counting it (breaks).
inline bool bond_fails(ForceContext& c, std::size_t b, double u, double uc, int& events, int& breaks) {
  if (c.past_cutoff[b] == 0) {
    c.past_cutoff[b] = 1;
    ++events;
  }
  if (!(u > uc + c.break_extra)) return false;
  ++breaks;
  c.status[b] = c.freeze ? kFreezing : kBroken;
  return true;
}

// After the evaluation that froze them: the kFreezing bonds of nodes [i0, i1) become kBroken.
void settle_failures(ForceContext& c, std::size_t i0, std::size_t i1);

}  // namespace frac::rubber
