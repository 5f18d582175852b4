#include "mesh/check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/polygon.hpp"
#include "mesh/cell_overlaps.hpp"

namespace frac::mesh {
namespace {

using geometry::cross;

// Collects failure lines, keeping the report short: after `limit` lines of one kind only a count.
class Failures {
 public:
  explicit Failures(std::vector<std::string>& out) : out_(out) {}
  ~Failures() {
    for (const auto& [kind, count] : dropped_) {
      out_.push_back(kind + ": " + std::to_string(count) + " more");
    }
  }
  Failures(const Failures&) = delete;
  Failures& operator=(const Failures&) = delete;
  void add(const std::string& kind, const std::string& detail) {
    auto& n = shown_[kind];
    if (n < limit) {
      out_.push_back(kind + ": " + detail);
      ++n;
    } else {
      ++dropped_[kind];
    }
  }

 private:
  static constexpr int limit = 10;
  std::vector<std::string>& out_;
  std::map<std::string, int> shown_;
  std::map<std::string, std::int64_t> dropped_;
};

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}

std::string histogram_line(const std::map<int, std::int64_t>& h, std::size_t total) {
  std::ostringstream s;
  s.precision(3);
  bool first = true;
  for (const auto& [k, count] : h) {
    s << (first ? "" : ", ") << k << ": " << count;
    if (total > 0) s << " (" << 100.0 * static_cast<double>(count) / static_cast<double>(total) << "%)";
    first = false;
  }
  return s.str();
}

// Length of the side shared by two convex counter-clockwise polygons that touch along a segment:
// the summed overlap of every pair of antiparallel edges, one of each polygon, lying on a common
// line (the other polygon's edge ends within `tol` of the line). Only real edges count, so a short
// side next to the shared one does not lengthen it.
double shared_side(std::span<const Vec2> p, std::span<const Vec2> q, double tol) {
  const std::size_t np = p.size(), nq = q.size();
  double total = 0.0;
  for (std::size_t i = 0; i < np; ++i) {
    const Vec2& a = p[i];
    const Vec2 e = p[(i + 1) % np] - a;
    const double len = e.norm();
    if (len == 0.0) continue;
    const Vec2 u = e / len;
    for (std::size_t j = 0; j < nq; ++j) {
      const Vec2& c = q[j];
      const Vec2& d = q[(j + 1) % nq];
      if (std::abs(cross(u, c - a)) > tol || std::abs(cross(u, d - a)) > tol) continue;
      // Projections on the edge of p: [0, len] and the interval spanned by q's edge (antiparallel).
      const double tc = u.dot(c - a), td = u.dot(d - a);
      if (td >= tc) continue;  // same direction: not a side shared by cells on opposite sides
      total += std::max(0.0, std::min(len, tc) - std::max(0.0, td));
    }
  }
  return total;
}

// Cells meet along sides only: pairs that overlap by more than a penetration of `len_tol` (mesh/cell_overlaps),
// at most the failures shown of a kind.
void check_overlaps(const CellMesh& m, double len_tol, double g, Failures& fail) {
  const OverlapSearch s = find_cell_overlaps(m, len_tol, g, 10);
  for (const CellOverlap& o : s.found) {
    const double smaller = std::min(m.area[o.a], m.area[o.b]);
    const std::string by = std::isnan(o.area)
                               ? ""
                               : " by " + fmt(o.area) + " m^2 (" + std::to_string(std::lround(100 * o.area / smaller)) +
                                     "% of the smaller)";
    fail.add("overlap", "cells " + std::to_string(o.a) + " and " + std::to_string(o.b) + " overlap" + by +
                            ", centroids " + fmt((m.centroid[o.b] - m.centroid[o.a]).norm()) + " m apart");
  }
  if (!s.complete)
    fail.add("overlap", "not checked: cell " + std::to_string(s.widest) +
                            " reaches so far beyond the others that "
                            "comparing the cells would take more than linear time");
}

// The arrays of a cell mesh agree in size, and every cell has at least 3 vertices. Nothing else can be
// checked (nor indexed) otherwise.
bool cell_arrays_consistent(const CellMesh& m, Failures& fail) {
  const std::size_t n = m.cells();
  bool arrays_ok = true;
  if (m.vertex_offset.size() != n + 1) {
    fail.add("arrays", "vertex_offset has " + std::to_string(m.vertex_offset.size()) + " entries, expected " +
                           std::to_string(n + 1));
    arrays_ok = false;
  } else if (m.vertex_offset.front() != 0 || m.vertex_offset.back() != static_cast<std::int64_t>(m.vertex.size())) {
    fail.add("arrays", "vertex_offset must run from 0 to the number of vertices");
    arrays_ok = false;
  }
  if (m.area.size() != n || m.second_moment.size() != n) {
    fail.add("arrays", "area/second_moment sizes differ from the number of cells");
    arrays_ok = false;
  }
  if (m.beam_length.size() != m.beams() || m.beam_section.size() != m.beams()) {
    fail.add("arrays", "beam_length/beam_section sizes differ from the number of beams");
    arrays_ok = false;
  }
  // In order from offset 0: each step is taken only from an offset already known to lie in
  // [0, vertices], so the difference cannot overflow.
  for (std::size_t k = 0; arrays_ok && k < n; ++k) {
    if (m.vertex_offset[k + 1] < m.vertex_offset[k] || m.vertex_offset[k + 1] - m.vertex_offset[k] < 3) {
      fail.add("arrays", "cell " + std::to_string(k) + " has fewer than 3 vertices (or offsets decrease)");
      arrays_ok = false;
    }
  }
  return arrays_ok;
}

// Finite values first: a NaN or an infinity makes every later comparison meaningless.
bool cell_values_finite(const CellMesh& m, Failures& fail) {
  const std::size_t n = m.cells();
  auto finite = [](const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); };
  bool all_finite = true;
  auto non_finite = [&](const std::string& what) {
    fail.add("finite", what + " is not finite");
    all_finite = false;
  };
  for (std::size_t k = 0; k < n; ++k) {
    auto id = [&] { return "cell " + std::to_string(k); };
    if (!finite(m.centroid[k])) non_finite(id() + ": centroid");
    if (!std::isfinite(m.area[k])) non_finite(id() + ": area");
    if (!std::isfinite(m.second_moment[k])) non_finite(id() + ": second_moment");
    const auto poly = m.polygon(k);
    for (std::size_t j = 0; j < poly.size(); ++j)
      if (!finite(poly[j])) {
        non_finite(id() + ": vertex " + std::to_string(j));
        break;
      }
  }
  for (std::size_t e = 0; e < m.beams(); ++e) {
    if (!std::isfinite(m.beam_length[e])) non_finite("beam " + std::to_string(e) + ": length");
    if (!std::isfinite(m.beam_section[e])) non_finite("beam " + std::to_string(e) + ": section");
  }
  if (!std::isfinite(m.spacing)) non_finite("attribute spacing");
  for (const double b : m.bounds)
    if (!std::isfinite(b)) {
      non_finite("attribute bounds");
      break;
    }
  return all_finite;
}

// Each cell: centroid in the box, convex and counter-clockwise, body frame about its centroid, area and
// second moment those of its vertices.
void check_cells(const CellMesh& m, double len_tol, double rel_tol, Failures& fail) {
  const auto& box = m.bounds;
  for (std::size_t k = 0; k < m.cells(); ++k) {
    const auto poly = m.polygon(k);
    auto id = [&] { return std::string("cell " + std::to_string(k)); };
    const Vec2& p = m.centroid[k];
    if (!(p.x() >= box[0] - len_tol && p.x() <= box[2] + len_tol && p.y() >= box[1] - len_tol &&
          p.y() <= box[3] + len_tol))
      fail.add("bounds", id() + ": centroid (" + fmt(p.x()) + ", " + fmt(p.y()) + ") lies outside the box");
    if (!geometry::is_convex_ccw(poly, 1e-9)) fail.add("convex", id() + " is not convex and counter-clockwise");
    const Vec2 c = geometry::centroid(poly);
    if (!(c.norm() <= len_tol)) {
      fail.add("centroid", id() + ": body-frame centroid at distance " + fmt(c.norm()) + " m");
    }
    const double a = geometry::signed_area(poly);
    if (!(m.area[k] > 0)) {
      fail.add("area", id() + ": area " + fmt(m.area[k]) + " m^2 is not positive");
    } else if (!(std::abs(a - m.area[k]) <= rel_tol * std::abs(a))) {
      fail.add("area", id() + ": area " + fmt(m.area[k]) + " m^2, vertices give " + fmt(a));
    }
    const double j = geometry::polar_second_moment(poly);
    if (!(std::abs(j - m.second_moment[k]) <= rel_tol * std::abs(j))) {
      fail.add("second_moment", id() + ": " + fmt(m.second_moment[k]) + " m^4, vertices give " + fmt(j));
    }
  }
}

// Link e of `links` (a mesh's beams or bonds, named `link`, joining `end`s of which there are n): ends in range,
// distinct and in order, links sorted without repeats. Returns false when its ends cannot be used.
bool check_link(const std::vector<std::array<std::int64_t, 2>>& links, std::size_t e, std::size_t n,
                const std::string& link, const std::string& end, const std::string& id, Failures& fail) {
  const auto [a, b] = links[e];
  if (a < 0 || b < 0 || a >= static_cast<std::int64_t>(n) || b >= static_cast<std::int64_t>(n)) {
    fail.add(link + " index", id + " out of range");
    return false;
  }
  if (a == b) {
    fail.add(link + " order", id + " joins a " + end + " to itself");
    return false;
  }
  if (a > b) fail.add(link + " order", id + ": need " + end + "_a < " + end + "_b");
  if (e > 0 && !(links[e - 1] < links[e])) {
    fail.add(links[e - 1] == links[e] ? link + " duplicate" : link + " order",
             id + " follows " + std::to_string(links[e - 1][0]) + ", " + std::to_string(links[e - 1][1]));
  }
  return true;
}

// Each beam: cells in range, distinct and in order, beams sorted without repeats, its length the distance
// of the centroids and its section the side the two cells share. Counts the beams of each cell in `degree`.
void check_beams(const CellMesh& m, double len_tol, Failures& fail, std::vector<int>& degree) {
  const std::size_t n = m.cells();
  std::vector<Vec2> pa, pb;
  for (std::size_t e = 0; e < m.beams(); ++e) {
    const auto [a, b] = m.beam[e];
    auto id = [&] {
      return std::string("beam " + std::to_string(e) + " (" + std::to_string(a) + ", " + std::to_string(b) + ")");
    };
    if (!check_link(m.beam, e, n, "beam", "cell", id(), fail)) continue;
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    ++degree[ua];
    ++degree[ub];
    const double l0 = (m.centroid[ub] - m.centroid[ua]).norm();
    if (!(m.beam_length[e] > 0)) {
      fail.add("beam length", id() + ": " + fmt(m.beam_length[e]) + " m is not positive");
    } else if (!(std::abs(m.beam_length[e] - l0) <= len_tol)) {
      fail.add("beam length", id() + ": " + fmt(m.beam_length[e]) + " m, centroids " + fmt(l0) + " m apart");
    }
    if (!(m.beam_section[e] > 0.0)) {
      fail.add("beam section", id() + ": section " + fmt(m.beam_section[e]) + " m is not positive");
      continue;
    }
    pa.clear();  // world polygons in reused buffers
    pb.clear();
    for (const auto& v : m.polygon(ua)) pa.push_back(v + m.centroid[ua]);
    for (const auto& v : m.polygon(ub)) pb.push_back(v + m.centroid[ub]);
    const double s = shared_side(pa, pb, len_tol);
    if (!(std::abs(m.beam_section[e] - s) <= len_tol)) {
      fail.add("beam section", id() + ": section " + fmt(m.beam_section[e]) + " m, shared side " + fmt(s) + " m");
    }
  }
}

std::string cell_mesh_summary(const CellMesh& m, double total_area, const std::map<int, std::int64_t>& neighbours) {
  const std::size_t n = m.cells();
  std::ostringstream s;
  s.precision(6);
  s << "cells: " << n << " (" << (m.shape.empty() ? "?" : m.shape) << ", spacing " << m.spacing << " m, disorder "
    << m.disorder << ", region " << m.disorder_region << ")\n";
  s << "beams: " << m.beams() << " (" << (n > 0 ? 2.0 * static_cast<double>(m.beams()) / static_cast<double>(n) : 0.0)
    << " per cell)\n";
  s << "total area: " << total_area << " m^2, mean area: " << total_area / static_cast<double>(n) << " m^2\n";
  s << "beams per cell: " << histogram_line(neighbours, n) << "\n";
  return s.str();
}

// The node mesh's counts and arrays agree; false when the bond arrays do not (nothing else can be checked).
bool node_arrays_consistent(const NodeMesh& m, Failures& fail) {
  const std::size_t n = m.nodes();
  if (n < 2) fail.add("nodes", "need at least 2, have " + std::to_string(n));
  if (m.nx < 0 || m.ny < 0) {
    fail.add("nodes", "nx = " + std::to_string(m.nx) + ", ny = " + std::to_string(m.ny) + ": negative");
  } else if (m.nx > 0 && m.ny > 0 &&
             (m.nx > static_cast<std::int64_t>(n) / m.ny || m.nx * m.ny != static_cast<std::int64_t>(n))) {
    fail.add("nodes",
             std::to_string(n) + " positions but nx * ny = " + std::to_string(m.nx) + " * " + std::to_string(m.ny));
  }
  if (m.bond_length.size() != m.bonds() || m.intact.size() != m.bonds()) {
    fail.add("arrays", "bond_length/intact sizes differ from the number of bonds");
    return false;
  }
  return true;
}

bool node_values_finite(const NodeMesh& m, Failures& fail) {
  bool all_finite = true;
  auto non_finite = [&](const std::string& what) {
    fail.add("finite", what + " is not finite");
    all_finite = false;
  };
  for (std::size_t k = 0; k < m.nodes(); ++k) {
    if (!std::isfinite(m.position[k].x()) || !std::isfinite(m.position[k].y()))
      non_finite("node " + std::to_string(k) + ": position");
  }
  for (std::size_t e = 0; e < m.bonds(); ++e)
    if (!std::isfinite(m.bond_length[e])) non_finite("bond " + std::to_string(e) + ": length");
  if (!std::isfinite(m.spacing)) non_finite("attribute spacing");
  if (!std::isfinite(m.notch_length)) non_finite("attribute notch_length");
  if (!std::isfinite(m.notch_y)) non_finite("attribute notch_y");
  return all_finite;
}

// Each bond: nodes in range, distinct and in order, bonds sorted without repeats, its length the distance
// of the nodes, intact 0 or 1. Counts the intact bonds of each node in `degree`; returns the intact bonds.
std::int64_t check_bonds(const NodeMesh& m, Failures& fail, std::vector<int>& degree) {
  const std::size_t n = m.nodes();
  std::int64_t intact = 0;
  for (std::size_t e = 0; e < m.bonds(); ++e) {
    const auto [a, b] = m.bond[e];
    auto id = [&] {
      return std::string("bond " + std::to_string(e) + " (" + std::to_string(a) + ", " + std::to_string(b) + ")");
    };
    if (!check_link(m.bond, e, n, "bond", "node", id(), fail)) continue;
    const double dist = (m.position[static_cast<std::size_t>(b)] - m.position[static_cast<std::size_t>(a)]).norm();
    const double scale = m.spacing > 0.0 ? m.spacing : m.bond_length[e];
    if (!(m.bond_length[e] > 0)) {
      fail.add("bond length", id() + ": " + fmt(m.bond_length[e]) + " m is not positive");
    } else if (!(std::abs(m.bond_length[e] - dist) <= 1e-9 * scale)) {
      fail.add("bond length", id() + ": " + fmt(m.bond_length[e]) + " m, nodes " + fmt(dist) + " m apart");
    }
    if (m.intact[e] > 1) fail.add("intact", id() + ": intact must be 0 or 1");
    if (m.intact[e] == 1) {
      ++intact;
      ++degree[static_cast<std::size_t>(a)];
      ++degree[static_cast<std::size_t>(b)];
    }
  }
  return intact;
}

std::string node_mesh_summary(const NodeMesh& m, std::int64_t intact, const std::map<int, std::int64_t>& neighbours) {
  std::ostringstream s;
  s.precision(6);
  s << "nodes: " << m.nodes() << " (" << m.nx << " x " << m.ny << ")\n";
  s << "bonds: " << m.bonds() << " (intact " << intact << ", cut " << static_cast<std::int64_t>(m.bonds()) - intact
    << ")\n";
  s << "spacing: " << m.spacing << " m, close-packed rows along " << m.rows_along << "\n";
  if (m.notch_length > 0.0) {
    s << "notch: " << m.notch_length << " m from the left edge along y = " << m.notch_y << " m\n";
  } else {
    s << "notch: none\n";
  }
  s << "intact bonds per node: " << histogram_line(neighbours, m.nodes()) << "\n";
  return s.str();
}

}  // namespace

// Tolerances are relative to the grid spacing g (or sqrt of the mean area when the spacing is not
// set): 1e-8 g for lengths. The generator merges Voronoi vertices closer than 1e-9 g and the rest is
// round-off of order 1e-16 of the coordinates, so 1e-8 g leaves a margin of 10 while still catching
// any real error. Areas and second moments: 1e-9 relative (they are recomputed from the same vertices).
// Every comparison is written so that a NaN fails it; values of any size are safe (no overflow in
// integer arithmetic, no index taken from a value not yet checked).
MeshReport check_cell_mesh(const CellMesh& m) {
  MeshReport r;
  {
    Failures fail(r.failures);  // its destructor appends the counts of failures not shown
    [&] {
      const std::size_t n = m.cells();
      if (n == 0) fail.add("cells", "none");
      if (!cell_arrays_consistent(m, fail)) return;
      if (!cell_values_finite(m, fail)) return;

      double total_area = 0.0;
      for (std::size_t k = 0; k < n; ++k) total_area += m.area[k];
      const double mean_size = std::sqrt(std::abs(total_area) / static_cast<double>(n));
      if (m.spacing < 0) fail.add("spacing", fmt(m.spacing) + " m is negative");
      // The spacing sets every length tolerance: one far from the cells' size would pass anything.
      if (m.spacing > 0 && mean_size > 0 && !(m.spacing <= 100 * mean_size && m.spacing >= 0.01 * mean_size))
        fail.add("spacing", fmt(m.spacing) + " m, far from the cells' mean size " + fmt(mean_size) + " m");
      const double g = m.spacing > 0 ? m.spacing : mean_size;
      const double len_tol = 1e-8 * g;
      const double rel_tol = 1e-9;
      const auto& box = m.bounds;
      if (!(box[0] <= box[2] && box[1] <= box[3]))
        fail.add("bounds", "box (" + fmt(box[0]) + ", " + fmt(box[1]) + ") to (" + fmt(box[2]) + ", " + fmt(box[3]) +
                               ") is empty");

      std::vector<int> degree(n, 0);
      check_cells(m, len_tol, rel_tol, fail);
      check_beams(m, len_tol, fail, degree);
      if (r.failures.empty()) check_overlaps(m, len_tol, g, fail);  // (it needs convex cells, as checked)
      for (const int d : degree) ++r.neighbour_count[d];
      r.summary = cell_mesh_summary(m, total_area, r.neighbour_count);
    }();
  }
  return r;
}

// Tolerance: bond lengths equal the node distances within 1e-9 of the spacing (or of the bond length
// when the spacing is not set); positions are computed directly, so the round-off is ~1e-16.
// Non-finite values are reported first, and alone: every later comparison would be meaningless.
MeshReport check_node_mesh(const NodeMesh& m) {
  MeshReport r;
  {
    Failures fail(r.failures);  // its destructor appends the counts of failures not shown
    [&] {
      if (!node_arrays_consistent(m, fail)) return;
      if (!node_values_finite(m, fail)) return;
      if (m.spacing < 0) fail.add("spacing", fmt(m.spacing) + " m is negative");
      if (m.rows_along != "x" && m.rows_along != "y") fail.add("rows_along", "'" + m.rows_along + "': expected x or y");
      if (m.notch_length < 0) fail.add("notch", "notch_length " + fmt(m.notch_length) + " m is negative");

      std::vector<int> degree(m.nodes(), 0);
      const std::int64_t intact = check_bonds(m, fail, degree);
      for (const int d : degree) ++r.neighbour_count[d];
      r.summary = node_mesh_summary(m, intact, r.neighbour_count);
    }();
  }
  return r;
}

}  // namespace frac::mesh
