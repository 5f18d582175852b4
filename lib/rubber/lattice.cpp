#include "rubber/lattice.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace frac::rubber {
namespace {

std::string node_name(std::int64_t k) { return "node " + std::to_string(k); }

// Forward neighbour (i', j') of node (i, j) in slot s (0, 1, 2), before wrapping; layout of
// mesh/triangular_lattice.cpp.
std::array<std::int64_t, 2> forward(bool rows_along_x, std::int64_t i, std::int64_t j, int s) {
  if (rows_along_x) {
    const std::int64_t odd = j & 1;
    if (s == 0) return {i + 1, j};
    if (s == 1) return {i + odd, j + 1};
    return {i - 1 + odd, j + 1};
  }
  const std::int64_t odd = i & 1;
  if (s == 0) return {i + 1, j + odd};
  if (s == 1) return {i, j + 1};
  return {i - 1, j + odd};
}

// The mesh's bonds into the slots of their nodes, each checked to be a nearest-neighbour bond of the lattice.
void add_mesh_bonds(Lattice& L, const mesh::NodeMesh& m) {
  const std::size_t n = L.n;
  const double d = m.spacing;
  const double sixty = std::numbers::pi / 3;
  for (std::size_t k = 0; k < m.bond.size(); ++k) {
    const auto a = m.bond[k][0], b = m.bond[k][1];
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n || a == b)
      throw InputError("bond " + std::to_string(k) + " joins invalid nodes " + std::to_string(a) + ", " +
                       std::to_string(b));
    const double dx = L.rx[static_cast<std::size_t>(b)] - L.rx[static_cast<std::size_t>(a)];
    const double dy = L.ry[static_cast<std::size_t>(b)] - L.ry[static_cast<std::size_t>(a)];
    const double len = std::hypot(dx, dy);
    double th = std::atan2(dy, dx) - L.base_angle;
    const double sf = std::round(th / sixty);
    if (!(std::abs(len - d) <= 1e-6 * d && std::abs(th - sf * sixty) <= 1e-6)) {  // (a NaN fails too)
      throw InputError("bond " + std::to_string(k) + " (" + node_name(a) + " to " + node_name(b) +
                       ") is not a nearest-neighbour bond of a triangular lattice of spacing " + std::to_string(d) +
                       " m with rows along " + m.rows_along);
    }
    int s = static_cast<int>(sf);
    s = ((s % 6) + 6) % 6;
    const std::int64_t owner = s < 3 ? a : b, other = s < 3 ? b : a;
    const int fs = s < 3 ? s : s - 3;
    const std::size_t id = 3 * static_cast<std::size_t>(owner) + static_cast<std::size_t>(fs);
    if (L.exists[id]) throw InputError("bond " + std::to_string(k) + " duplicates another bond of " + node_name(owner));
    L.exists[id] = 1;
    L.intact[id] = (k < m.intact.size() && m.intact[k] == 0) ? 0 : 1;
    L.mesh_bond[id] = static_cast<std::int64_t>(k);
    L.bond_id[k] = static_cast<std::int64_t>(id);
    L.nbr[6 * static_cast<std::size_t>(owner) + static_cast<std::size_t>(fs)] = static_cast<std::int32_t>(other);
    L.nbr[6 * static_cast<std::size_t>(other) + static_cast<std::size_t>(fs + 3)] = static_cast<std::int32_t>(owner);
  }
}

// The periodic box and the parity of the periods it needs.
void set_periodic_box(Lattice& L, const mesh::NodeMesh& m, bool periodic_x, bool periodic_y) {
  const std::size_t n = L.n;
  const double d = m.spacing;
  const std::int64_t nx = m.nx, ny = m.ny;
  if (nx * ny != static_cast<std::int64_t>(n)) throw InputError("periodic boundaries need an nx x ny mesh");
  const double h = d * std::sqrt(3.0) / 2;
  // Periods and the parity they must respect.
  if (L.rows_along_x) {
    if (periodic_x && nx < 3)
      throw UsageError("periodic in x needs at least 3 nodes per row, got " + std::to_string(nx));
    if (periodic_y && (ny < 4 || ny % 2))
      throw UsageError("periodic in y needs an even number (>= 4) of rows, got " + std::to_string(ny));
    L.box_x = periodic_x ? static_cast<double>(nx) * d : 0;
    L.box_y = periodic_y ? static_cast<double>(ny) * h : 0;
  } else {
    if (periodic_x && (nx < 4 || nx % 2))
      throw UsageError("periodic in x needs an even number (>= 4) of columns, got " + std::to_string(nx));
    if (periodic_y && ny < 3)
      throw UsageError("periodic in y needs at least 3 nodes per column, got " + std::to_string(ny));
    L.box_x = periodic_x ? static_cast<double>(nx) * h : 0;
    L.box_y = periodic_y ? static_cast<double>(ny) * d : 0;
  }
}

// The wrap bonds follow the index layout of mesh-gen triangular: each node where that layout puts it.
void check_periodic_layout(const Lattice& L, const mesh::NodeMesh& m) {
  const std::int64_t nx = m.nx, ny = m.ny;
  const double d = m.spacing, h = d * std::sqrt(3.0) / 2;
  for (std::int64_t j = 0; j < ny; ++j)
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto k = static_cast<std::size_t>(j * nx + i);
      const double ex =
          L.rows_along_x ? static_cast<double>(i) * d + ((j & 1) ? d / 2 : 0) : static_cast<double>(i) * h;
      const double ey =
          L.rows_along_x ? static_cast<double>(j) * h : static_cast<double>(j) * d + ((i & 1) ? d / 2 : 0);
      if (std::abs(L.rx[k] - ex - L.rx[0]) > 1e-6 * d || std::abs(L.ry[k] - ey - L.ry[0]) > 1e-6 * d)
        throw InputError("periodic boundaries need the node layout of mesh-gen triangular; " +
                         node_name(static_cast<std::int64_t>(k)) + " is out of place");
    }
}

// The bonds across the periodic boundaries, with the image shifts of their far ends.
void add_wrap_bonds(Lattice& L, const mesh::NodeMesh& m, bool periodic_x, bool periodic_y) {
  const std::int64_t nx = m.nx, ny = m.ny;
  for (std::int64_t j = 0; j < ny; ++j)
    for (std::int64_t i = 0; i < nx; ++i)
      for (int s = 0; s < 3; ++s) {
        auto [ti, tj] = forward(L.rows_along_x, i, j, s);
        double sx = 0, sy = 0;
        bool wrapped = false;
        if (ti < 0 || ti >= nx) {
          if (!periodic_x) continue;
          sx = ti < 0 ? -L.box_x : L.box_x;
          ti = (ti + nx) % nx;
          wrapped = true;
        }
        if (tj < 0 || tj >= ny) {
          if (!periodic_y) continue;
          sy = tj < 0 ? -L.box_y : L.box_y;
          tj = (tj + ny) % ny;
          wrapped = true;
        }
        if (!wrapped) continue;
        const auto owner = static_cast<std::size_t>(j * nx + i), other = static_cast<std::size_t>(tj * nx + ti);
        const std::size_t id = 3 * owner + static_cast<std::size_t>(s);
        L.exists[id] = 1;
        L.intact[id] = 1;
        L.shift[2 * id] = sx;
        L.shift[2 * id + 1] = sy;
        L.nbr[6 * owner + static_cast<std::size_t>(s)] = static_cast<std::int32_t>(other);
        L.nbr[6 * other + static_cast<std::size_t>(s + 3)] = static_cast<std::int32_t>(owner);
      }
}

}  // namespace

Lattice build_lattice(const mesh::NodeMesh& m, bool periodic_x, bool periodic_y) {
  Lattice L;
  L.n = m.position.size();
  L.spacing = m.spacing;
  L.nx = m.nx;
  L.ny = m.ny;
  L.rows_along_x = m.rows_along != "y";
  L.base_angle = L.rows_along_x ? 0.0 : std::numbers::pi / 6;
  L.periodic_x = periodic_x;
  L.periodic_y = periodic_y;
  const std::size_t n = L.n;
  if (n == 0) throw InputError("the mesh has no nodes");
  if (n >= static_cast<std::size_t>(INT32_MAX)) throw InputError("the mesh has too many nodes for the rubber lattice");
  if (!(m.spacing > 0)) throw InputError("the mesh has no valid lattice spacing");
  for (int s = 0; s < 6; ++s) {
    const double th = L.base_angle + s * std::numbers::pi / 3;
    L.slot_dir[2 * static_cast<std::size_t>(s)] = std::cos(th);
    L.slot_dir[2 * static_cast<std::size_t>(s) + 1] = std::sin(th);
  }
  L.rx.resize(n);
  L.ry.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    L.rx[i] = m.position[i].x();
    L.ry[i] = m.position[i].y();
  }
  const std::size_t nb = L.bonds();
  L.nbr.assign(6 * (n + 1), static_cast<std::int32_t>(n));
  L.exists.assign(nb, 0);
  L.intact.assign(nb, 0);
  L.mesh_bond.assign(nb, -1);
  L.shift.assign(2 * nb, 0.0);
  L.bond_id.assign(m.bond.size(), -1);

  add_mesh_bonds(L, m);
  if (periodic_x || periodic_y) {
    set_periodic_box(L, m, periodic_x, periodic_y);
    check_periodic_layout(L, m);
    add_wrap_bonds(L, m, periodic_x, periodic_y);
  }
  return L;
}

}  // namespace frac::rubber
