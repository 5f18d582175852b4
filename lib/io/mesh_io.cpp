#include "io/mesh_io.hpp"

#include <algorithm>
#include <initializer_list>
#include <new>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "mesh/check.hpp"

namespace frac::io {
namespace {

using mesh::Vec2;

std::span<const double> flat(const std::vector<Vec2>& v) {
  return {v.empty() ? nullptr : v.data()->data(), 2 * v.size()};
}
std::span<const std::int64_t> flat(const std::vector<std::array<std::int64_t, 2>>& v) {
  return {v.empty() ? nullptr : v.data()->data(), 2 * v.size()};
}

std::vector<Vec2> to_vec2(const std::vector<double>& flat_xy) {
  std::vector<Vec2> out(flat_xy.size() / 2);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Vec2(flat_xy[2 * k], flat_xy[2 * k + 1]);
  return out;
}
std::vector<std::array<std::int64_t, 2>> to_pairs(const std::vector<std::int64_t>& flat_ab) {
  std::vector<std::array<std::int64_t, 2>> out(flat_ab.size() / 2);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {flat_ab[2 * k], flat_ab[2 * k + 1]};
  return out;
}

void write_box(Group& particles, const std::array<double, 4>& bounds) {
  Group box = particles.create_group("box");
  box.set_attr("dimension", std::int64_t{2});
  box.set_attr("boundary", std::vector<std::string>{"none", "none"});
  box.set_attr("bounds", std::vector<double>(bounds.begin(), bounds.end()));
}

void require_pairs_in_range(const Group& g, std::string_view name, const std::vector<std::array<std::int64_t, 2>>& p,
                            std::size_t n) {
  for (std::size_t k = 0; k < p.size(); ++k)
    for (auto i : p[k])
      if (i < 0 || static_cast<std::size_t>(i) >= n)
        throw InputError(g.where(name) + ": row " + std::to_string(k) + " refers to index " + std::to_string(i) +
                         ", outside 0.." + std::to_string(n - 1));
}

}  // namespace

void write_mesh(Group& root, const mesh::CellMesh& m) {
  const hsize_t n = m.cells(), v = m.vertex.size(), b = m.beams();
  Group cells = root.create_group("particles/cells");
  cells.set_attr("shape", m.shape);
  cells.set_attr("spacing", m.spacing);
  cells.set_attr("disorder", m.disorder);
  cells.set_attr("disorder_region", m.disorder_region);
  write_box(cells, m.bounds);
  cells.write("vertex_offset", std::span<const std::int64_t>(m.vertex_offset), {n + 1});
  cells.write("vertex", flat(m.vertex), {v, 2}, "m");
  cells.write("centroid", flat(m.centroid), {n, 2}, "m");
  cells.write("area", std::span<const double>(m.area), {n}, "m^2");
  cells.write("second_moment", std::span<const double>(m.second_moment), {n}, "m^4");

  Group beams = root.create_group("connectivity/beams");
  beams.set_attr("particles_group", "/particles/cells");
  beams.write("pairs", flat(m.beam), {b, 2});
  beams.write("length", std::span<const double>(m.beam_length), {b}, "m");
  beams.write("section", std::span<const double>(m.beam_section), {b}, "m");
}

void write_mesh(Group& root, const mesh::NodeMesh& m) {
  const hsize_t n = m.nodes(), b = m.bonds();
  Group nodes = root.create_group("particles/nodes");
  nodes.set_attr("nx", m.nx);
  nodes.set_attr("ny", m.ny);
  nodes.set_attr("spacing", m.spacing);
  nodes.set_attr("rows_along", m.rows_along);
  nodes.set_attr("notch_length", m.notch_length);
  nodes.set_attr("notch_y", m.notch_y);
  std::array<double, 4> bounds{0, 0, 0, 0};
  if (!m.position.empty()) {
    bounds = {m.position[0].x(), m.position[0].y(), m.position[0].x(), m.position[0].y()};
    for (const auto& p : m.position) {
      bounds[0] = std::min(bounds[0], p.x());
      bounds[1] = std::min(bounds[1], p.y());
      bounds[2] = std::max(bounds[2], p.x());
      bounds[3] = std::max(bounds[3], p.y());
    }
  }
  write_box(nodes, bounds);
  nodes.write("reference_position", flat(m.position), {n, 2}, "m");

  Group bonds = root.create_group("connectivity/bonds");
  bonds.set_attr("particles_group", "/particles/nodes");
  bonds.write("pairs", flat(m.bond), {b, 2});
  bonds.write("length", std::span<const double>(m.bond_length), {b}, "m");
  bonds.write("intact", std::span<const std::uint8_t>(m.intact), {b});
}

MeshKind mesh_kind(const Group& root) {
  if (root.has("particles/cells") && root.has("connectivity/beams")) return MeshKind::cells;
  if (root.has("particles/nodes") && root.has("connectivity/bonds")) return MeshKind::nodes;
  throw InputError(root.file() +
                   ": holds no mesh (neither /particles/cells with /connectivity/beams "
                   "nor /particles/nodes with /connectivity/bonds)");
}

namespace {

// The datasets of group `g` that give the same count (rows, or rows - 1 for an offset list) must agree:
// InputError naming the first that differs from the most common count, and those it disagrees with.
void require_same_count(const Group& g, std::initializer_list<std::pair<const char*, std::size_t>> counts,
                        const char* what) {
  std::size_t majority = counts.begin()->second, best = 0;
  for (const auto& [name, n] : counts) {
    std::size_t votes = 0;
    for (const auto& c : counts) votes += c.second == n;
    if (votes > best) best = votes, majority = n;
  }
  for (const auto& [name, n] : counts) {
    if (n == majority) continue;
    std::string agree;
    for (const auto& c : counts)
      if (c.second == majority) agree += (agree.empty() ? "" : ", ") + std::string(c.first);
    throw InputError(g.where(name) + ": gives " + std::to_string(n) + " " + what + ", but " + agree + " give " +
                     std::to_string(majority));
  }
}

// InputError naming the first faults of `report` unless the mesh holds every invariant of mesh-gen check.
void require_valid(const Group& root, const mesh::MeshReport& report) {
  if (report.ok()) return;
  std::string msg = root.file() + ": invalid mesh: ";
  const std::size_t shown = std::min<std::size_t>(report.failures.size(), 3);
  for (std::size_t k = 0; k < shown; ++k) msg += (k ? "; " : "") + report.failures[k];
  if (report.failures.size() > shown) msg += "; and more (mesh-gen check " + root.file() + " lists them)";
  throw InputError(msg);
}

}  // namespace

mesh::CellMesh read_cell_mesh_as_stored(const Group& root) {
  mesh::CellMesh m;
  const Group cells = root.group("particles/cells");
  m.shape = cells.attr_string("shape");
  m.spacing = cells.attr_double("spacing");
  m.disorder = cells.attr_double("disorder");
  m.disorder_region = cells.attr_string("disorder_region");
  const auto bounds = cells.attr_doubles("bounds", "box");
  if (bounds.size() != 4) throw InputError(cells.where("box") + ": attribute 'bounds' must hold 4 values");
  std::copy(bounds.begin(), bounds.end(), m.bounds.begin());

  m.centroid = to_vec2(cells.read<double>("centroid", nullptr, 2, 2));
  m.vertex_offset = cells.read<std::int64_t>("vertex_offset", nullptr, 1);
  m.vertex = to_vec2(cells.read<double>("vertex", nullptr, 2, 2));
  m.area = cells.read<double>("area", nullptr, 1);
  m.second_moment = cells.read<double>("second_moment", nullptr, 1);
  const std::size_t n = m.area.size();
  if (m.vertex_offset.empty()) throw InputError(cells.where("vertex_offset") + ": empty (it holds cells + 1 offsets)");
  require_same_count(cells,
                     {{"area", n},
                      {"centroid", m.centroid.size()},
                      {"second_moment", m.second_moment.size()},
                      {"vertex_offset", m.vertex_offset.size() - 1}},
                     "cells");
  if (m.vertex_offset.front() != 0 || m.vertex_offset.back() != static_cast<std::int64_t>(m.vertex.size()))
    throw InputError(cells.where("vertex_offset") + ": must run from 0 to the number of vertices (" +
                     std::to_string(m.vertex.size()) + ")");
  for (std::size_t k = 0; k < n; ++k)
    if (m.vertex_offset[k + 1] < m.vertex_offset[k])
      throw InputError(cells.where("vertex_offset") + ": decreases at cell " + std::to_string(k));

  const Group beams = root.group("connectivity/beams");
  m.beam = to_pairs(beams.read<std::int64_t>("pairs", nullptr, 2, 2));
  m.beam_length = beams.read<double>("length", nullptr, 1);
  m.beam_section = beams.read<double>("section", nullptr, 1);
  require_same_count(
      beams, {{"pairs", m.beam.size()}, {"length", m.beam_length.size()}, {"section", m.beam_section.size()}}, "beams");
  require_pairs_in_range(beams, "pairs", m.beam, n);
  return m;
}

mesh::NodeMesh read_node_mesh_as_stored(const Group& root) {
  mesh::NodeMesh m;
  const Group nodes = root.group("particles/nodes");
  m.nx = nodes.attr_int("nx");
  m.ny = nodes.attr_int("ny");
  m.spacing = nodes.attr_double("spacing");
  m.rows_along = nodes.attr_string("rows_along");
  m.notch_length = nodes.attr_double("notch_length");
  m.notch_y = nodes.attr_double("notch_y");
  m.position = to_vec2(nodes.read<double>("reference_position", nullptr, 2, 2));
  const auto rows = static_cast<std::int64_t>(m.position.size());
  std::int64_t product = 0;  // (nx and ny come from the file: their product may overflow)
  if (m.nx <= 0 || m.ny <= 0 || __builtin_mul_overflow(m.nx, m.ny, &product) || product != rows)
    throw InputError(nodes.where("reference_position") + ": has " + std::to_string(rows) +
                     " rows, but the attributes say nx = " + std::to_string(m.nx) + ", ny = " + std::to_string(m.ny));
  const Group bonds = root.group("connectivity/bonds");
  m.bond = to_pairs(bonds.read<std::int64_t>("pairs", nullptr, 2, 2));
  m.bond_length = bonds.read<double>("length", nullptr, 1);
  m.intact = bonds.read<std::uint8_t>("intact", nullptr, 1);
  require_same_count(bonds, {{"pairs", m.bond.size()}, {"length", m.bond_length.size()}, {"intact", m.intact.size()}},
                     "bonds");
  require_pairs_in_range(bonds, "pairs", m.bond, m.position.size());
  return m;
}

mesh::CellMesh read_cell_mesh(const Group& root) try {
  mesh::CellMesh m = read_cell_mesh_as_stored(root);
  require_valid(root, mesh::check_cell_mesh(m));
  return m;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the mesh of " + root.file());
}

mesh::NodeMesh read_node_mesh(const Group& root) try {
  mesh::NodeMesh m = read_node_mesh_as_stored(root);
  require_valid(root, mesh::check_node_mesh(m));
  return m;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the mesh of " + root.file());
}

}  // namespace frac::io
