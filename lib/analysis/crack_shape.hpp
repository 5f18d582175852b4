#pragma once
// The shape of a running crack in one frame of a rubber run (docs/rubber-run.md, "Crack experiment"):
// where its tip is, the angle of the front behind which the stretched sheet unloads (the wedge of the
// paper's Fig. 2, to compare with the Mach angle asin(c/v)), how far that front trails the tip, and
// whether the clamped rows hold.
//
// The mesh has close-packed rows along x (mesh-gen triangular), the crack line is its notch line, and
// the sheet was pre-stretched to (λx, λy). A node is unloaded when both of its bonds to the row above
// (upper half) or below (lower half) are broken or stretched less than half the far field's strain of
// those bonds: the material behind the front has let go of its stretch. In each row the front is the
// first unloaded node met coming from the far end (the far end is intact far field: a supersonic tip
// outruns every wave), with the next two nodes behind it unloaded too (a stray broken bond is not a
// front). The front's lab x against the row's far-field lab height, fitted by least squares over the
// rows between the crack line and the grips, gives the front's angle to the crack line (90° for a
// straight front across the strip) and its intercept on the crack line.
#include <cstddef>

#include "io/run_io.hpp"
#include "mesh/node_mesh.hpp"

namespace frac::analysis {

struct CrackShape {
  double time = 0;                  // s, of the frame
  bool tip_found = false;           // a crossing bond is broken
  double tip_reference_x = 0;       // m, reference x where the furthest broken crossing bond crosses the line
  double tip_x = 0;                 // m, lab x of that bond (mean of its nodes)
  std::size_t broken_crossing = 0;  // broken bonds across the crack line
  std::size_t broken_bulk = 0;      // broken bonds that do not cross it
  // The unloading front, each half of the strip fitted separately, and both together (the intercept
  // shared): angle to the crack line in degrees, NaN when fewer than 3 rows have a front.
  double front_angle_upper = 0, front_angle_lower = 0, front_angle = 0;
  std::size_t front_rows = 0;         // rows with a front, both halves
  double front_rms = 0;               // m, rms distance of the rows' fronts from the fitted lines (along x)
  double front_lag = 0;               // m, tip x minus the fitted front's x on the crack line: how far the
                                      // opening trails the tip (≈ 0: a wedge with the tip at its apex)
  std::size_t grip_bonds = 0;         // bonds from the clamped rows to the free rows next to them, behind the tip
  std::size_t grip_bonds_broken = 0;  // of those, broken: the sheet tears off the grips
  std::size_t free_nodes = 0;         // nodes outside the clamped rows
  // Of those, beyond the outer rows by more than the unstretched height of the free half strip: debris flying
  // past the grips (a retracted half folded over its grip reaches no further).
  std::size_t nodes_past_grips = 0;
};

// `frame` of a run on `mesh` (rows along x; InputError otherwise); `stretch` the pre-stretch (λx, λy);
// `clamp_rows` the rows held at top and bottom.
CrackShape measure_crack_shape(const mesh::NodeMesh& mesh, const io::BodyFrame& frame, double stretch_x,
                               double stretch_y, std::size_t clamp_rows);

}  // namespace frac::analysis
