#include "mesh/triangular_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <sstream>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace frac::mesh {
namespace {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// The options make a lattice: at least 2 × 2 nodes, a positive spacing, rows along x or y, and a notch
// shorter than the lattice is wide.
void validate(const TriangularLatticeOptions& opt) {
  if (opt.nx < 2 || opt.ny < 2) {
    throw UsageError("--nodes: need at least 2 x 2 nodes, got " + std::to_string(opt.nx) + " x " +
                     std::to_string(opt.ny));
  }
  if (opt.nx > std::numeric_limits<std::int32_t>::max() / opt.ny) throw UsageError("--nodes: too many nodes");
  if (!(std::isfinite(opt.spacing) && opt.spacing > 0.0)) {
    throw UsageError("--spacing: must be positive and finite, got " + fmt(opt.spacing));
  }
  if (opt.rows_along != "x" && opt.rows_along != "y") {
    throw UsageError("--rows-along: must be 'x' or 'y', got '" + opt.rows_along + "'");
  }
  const double d = opt.spacing;
  const double h = d * std::sqrt(3.0) / 2.0;
  const double width =
      opt.rows_along == "x" ? static_cast<double>(opt.nx - 1) * d + 0.5 * d : static_cast<double>(opt.nx - 1) * h;
  if (!(std::isfinite(opt.notch) && opt.notch >= 0.0 && opt.notch < width)) {
    throw UsageError("--notch: must lie in [0, " + fmt(width) + ") m (the lattice width), got " + fmt(opt.notch));
  }
}

// Node (i, j) at index j nx + i (positions: see the layout above make_triangular_lattice).
void place_nodes(NodeMesh& m, bool along_x, double d, double h) {
  m.position.reserve(static_cast<std::size_t>(m.nx * m.ny));
  for (std::int64_t j = 0; j < m.ny; ++j) {
    for (std::int64_t i = 0; i < m.nx; ++i) {
      const auto di = static_cast<double>(i), dj = static_cast<double>(j);
      if (along_x) {
        m.position.emplace_back(di * d + ((j % 2 == 1) ? 0.5 * d : 0.0), dj * h);
      } else {
        m.position.emplace_back(di * h, dj * d + ((i % 2 == 1) ? 0.5 * d : 0.0));
      }
    }
  }
}

// Each node's bonds along its row (column) and to the next row (column), sorted, all intact, of length d.
void add_bonds(NodeMesh& m, bool along_x, double d) {
  const std::int64_t nx = m.nx, ny = m.ny;
  auto index = [nx](std::int64_t i, std::int64_t j) { return j * nx + i; };
  auto add = [&m](std::int64_t a, std::int64_t b) { m.bond.push_back({std::min(a, b), std::max(a, b)}); };
  m.bond.reserve(static_cast<std::size_t>(3 * nx * ny));
  for (std::int64_t j = 0; j < ny; ++j) {
    for (std::int64_t i = 0; i < nx; ++i) {
      const std::int64_t a = index(i, j);
      if (along_x) {
        if (i + 1 < nx) add(a, index(i + 1, j));
        if (j + 1 < ny) {
          const std::int64_t lo = (j % 2 == 0) ? i - 1 : i;  // the two nodes above: lo and lo + 1
          if (lo >= 0) add(a, index(lo, j + 1));
          if (lo + 1 < nx) add(a, index(lo + 1, j + 1));
        }
      } else {
        if (j + 1 < ny) add(a, index(i, j + 1));
        if (i + 1 < nx) {
          const std::int64_t lo = (i % 2 == 0) ? j - 1 : j;  // the two nodes to the right: lo and lo + 1
          if (lo >= 0) add(a, index(i + 1, lo));
          if (lo + 1 < ny) add(a, index(i + 1, lo + 1));
        }
      }
    }
  }
  std::sort(m.bond.begin(), m.bond.end());
  m.bond_length.assign(m.bond.size(), d);
  m.intact.assign(m.bond.size(), 1);
}

// The notch line notch_y between the two middle node heights (see above make_triangular_lattice), and the
// bonds across it within notch_length of the left edge cut.
void cut_notch(NodeMesh& m, bool along_x, double d, double h) {
  // Distinct heights: j h (rows along x) or j D / 2 (rows along y, nx >= 2 gives both parities).
  const std::int64_t levels = along_x ? m.ny : 2 * m.ny;
  const double level_step = along_x ? h : 0.5 * d;
  const std::int64_t lower = (levels - 1) / 2;
  m.notch_y = (static_cast<double>(lower) + 0.5) * level_step;
  if (m.notch_length > 0.0) {
    const double x_min = 0.0;  // the even rows (or column 0) start at x = 0
    for (std::size_t e = 0; e < m.bond.size(); ++e) {
      const Vec2& p = m.position[static_cast<std::size_t>(m.bond[e][0])];
      const Vec2& q = m.position[static_cast<std::size_t>(m.bond[e][1])];
      const double sp = p.y() - m.notch_y, sq = q.y() - m.notch_y;
      if ((sp < 0.0) == (sq < 0.0)) continue;
      const double x_cross = p.x() + (q.x() - p.x()) * sp / (sp - sq);
      if (x_cross - x_min < m.notch_length) m.intact[e] = 0;
    }
  }
}

}  // namespace

// Layout. rows_along "x": node (i, j) at (i D + (j odd ? D/2 : 0), j D sqrt(3)/2); node (i, j) is
// bonded to (i+1, j) and, in row j+1, to (i-1, j+1), (i, j+1) for even j or (i, j+1), (i+1, j+1) for
// odd j. rows_along "y" is the same lattice turned by 90 degrees: node (i, j) at
// (i D sqrt(3)/2, j D + (i odd ? D/2 : 0)), bonded to (i, j+1) and, in column i+1, to (i+1, j-1),
// (i+1, j) for even i or (i+1, j), (i+1, j+1) for odd i. Either way there are
// (nx-1) ny + (ny-1)(2nx-1) = 3 nx ny - 2 nx - 2 ny + 1 bonds for rows along x and
// nx (ny-1) + (nx-1)(2ny-1) = the same number for rows along y.
//
// Notch: the distinct node heights are sorted and notch_y is the midpoint of the two middle ones,
// levels (m-1)/2 and (m-1)/2 + 1 of m (integer division: for odd m the line runs just above the middle
// level). A bond is cut when its ends lie on opposite sides of notch_y and the line crosses it at
// x - x_min < L. notch_y is recorded even without a notch (the line a crack would follow).
NodeMesh make_triangular_lattice(const TriangularLatticeOptions& opt) try {
  validate(opt);
  const bool along_x = opt.rows_along == "x";
  const double d = opt.spacing;
  const double h = d * std::sqrt(3.0) / 2.0;

  NodeMesh m;
  m.nx = opt.nx;
  m.ny = opt.ny;
  m.spacing = d;
  m.rows_along = opt.rows_along;
  m.notch_length = opt.notch;
  place_nodes(m, along_x, d, h);
  add_bonds(m, along_x, d);
  cut_notch(m, along_x, d, h);
  return m;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the lattice of " + std::to_string(opt.nx) + " x " + std::to_string(opt.ny) + " nodes");
}

}  // namespace frac::mesh
