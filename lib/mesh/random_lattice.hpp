#pragma once
// The vectorizable random lattice (Moukarzel & Herrmann 1992): one Voronoi site thrown in each cell
// of a square grid of spacing g, inside a square of side a = disorder * g centred in the cell (or a
// disc of radius a), cut to a rectangle (cells clipped to the box) or to a disc (whole cells of a
// square tessellation whose centroid lies within the radius). See docs/physics/polygon-dem.md §1.
//
// Conventions. Rectangle: box [0, W] x [0, H], g = W / nx, which must equal H / ny within 1e-9
// relative; cell j nx + i comes from grid cell (i, j). Disc: centred on the origin, g = sqrt(pi R^2 /
// cells), a square grid covering [-R - 4g, R + 4g]^2 is tessellated and the cells whose centroid lies
// within R are kept, numbered in grid order (so the count only approximates `cells`); bounds =
// [-R, R]^2, cell vertices reach up to about 2 sqrt(2) g beyond R. Random numbers: frac::Rng(seed), two
// uniforms per grid cell in grid order (x then y; the disc region draws by rejection from [-a, a]^2).
// A site thrown outside the box (disc region with a > g/2, boundary cells) is mirrored back across
// the box side. Vertices closer than 1e-9 g are merged; beams need a shared side >= min_section g.
#include <cstdint>
#include <set>
#include <string>

#include "mesh/cell_mesh.hpp"

namespace frac::mesh {

struct RandomLatticeOptions {
  std::string shape = "rect";              // "rect" or "disc"
  double width = 0.0, height = 0.0;        // m, rectangle size
  std::int64_t nx = 0, ny = 0;             // rectangle: grid cells along x and y (spacing = width / nx)
  double diameter = 0.0;                   // m, disc diameter
  std::int64_t cells = 0;                  // disc: requested number of cells (spacing = sqrt(pi R^2 / cells))
  double disorder = 1.0;                   // a / g in [0, 1]
  std::string disorder_region = "square";  // "square" or "disc"
  std::uint64_t seed = 1;
  double min_section = 1e-6;  // beams whose shared side is below min_section * g are dropped
};

// Throws UsageError (naming the option) for invalid options.
CellMesh make_random_lattice(const RandomLatticeOptions& opt);

// UsageError naming an option given (`given`: long option names, as cli::given_options) that `opt` ignores:
// --size of a disc, --diameter of a rectangle. (--seed and --disorder-region at disorder 0 are kept: a sweep over
// the disorder at one seed passes them at every level.)
void refuse_ignored_options(const RandomLatticeOptions& opt, const std::set<std::string>& given);

}  // namespace frac::mesh
