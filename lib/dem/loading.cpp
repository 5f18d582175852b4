#include "dem/loading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/exact_sum.hpp"
#include "core/option_check.hpp"
#include "core/physical_limits.hpp"
#include "geometry/polygon.hpp"

namespace frac::dem {
namespace {

// Exact sums (core/exact_sum): the same value whatever the cells' order or, on several ranks, their split.
double sum_over(const std::vector<std::size_t>& cells, const double* values) {
  ExactSum s;
  for (std::size_t k : cells) s.add(values[k]);
  return s.value();
}

double mean(const std::vector<std::size_t>& cells, const double* coord) {
  return cells.empty() ? 0.0 : sum_over(cells, coord) / static_cast<double>(cells.size());
}

// Distance from point p to the boundary of polygon poly (world coordinates).
double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& poly) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < poly.size(); ++a) {
    const Vec2& u = poly[a];
    const Vec2& w = poly[(a + 1) % poly.size()];
    const Vec2 e = w - u;
    const double t = std::clamp((p - u).dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (u + t * e - p).norm());
  }
  return best;
}

// The explosion / pulse kick: every side of the explosive polygon is shared with one neighbour k,
// which gets v_k = C·S_k/m_k·n_k along the side's outward normal, C = sqrt(2 E0 / Σ S_k²/m_k):
// Σ ½ m v² = E0 and Σ m v = C Σ S_k n_k = 0 exactly (the sides of a closed polygon sum to zero).
LoadingSetup explosion_kick(const Loading& loading, const mesh::CellMesh& mesh, const Bodies& bodies,
                            std::span<double> v0) {
  LoadingSetup setup;
  const std::size_t n = mesh.cells();
  const Vec2 centre(0.5 * (mesh.bounds[0] + mesh.bounds[2]), 0.5 * (mesh.bounds[1] + mesh.bounds[3]));
  std::size_t src = 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((mesh.centroid[k] - centre).squaredNorm() < (mesh.centroid[src] - centre).squaredNorm()) src = k;
  setup.source = src;
  const auto poly = mesh.world_polygon(src);
  const double g = bodies.length_scale;
  struct Side {
    std::size_t cell;
    double s;
    Vec2 normal;
  };
  std::vector<Side> sides;
  for (std::size_t a = 0; a < poly.size(); ++a) {
    const Vec2 e = poly[(a + 1) % poly.size()] - poly[a];
    const Vec2 mid = poly[a] + 0.5 * e;
    const double len = e.norm();
    if (len <= 1e-12 * g) continue;
    const Vec2 normal(e.y() / len, -e.x() / len);  // outward for a counter-clockwise polygon
    std::size_t owner = n;
    double best = 1e-6 * g;
    for (std::size_t k = 0; k < n; ++k) {
      if (k == src || (mesh.centroid[k] - mid).norm() > 4 * g + 2 * bodies.max_bound_radius) continue;
      const double dist = distance_to_boundary(mid, mesh.world_polygon(k));
      if (dist < best) {
        best = dist;
        owner = k;
      }
    }
    if (owner == n)
      throw InputError("loading.kind = " + loading.name + ": the explosive cell " + std::to_string(src) +
                       " has a side on the sample's boundary; it must be an interior cell");
    sides.push_back({owner, len, normal});
  }
  double denom = 0;
  for (const auto& s : sides) denom += s.s * s.s / bodies.mass[s.cell];
  const double c = std::sqrt(2 * loading.energy / denom);
  for (const auto& s : sides) {
    const double speed = c * s.s / bodies.mass[s.cell];
    v0[s.cell] += speed * s.normal.x();
    v0[n + s.cell] += speed * s.normal.y();
    setup.kicked.push_back(s.cell);
  }
  setup.kinetic_energy = loading.energy;
  return setup;
}

// The projectile: the bottom-layer cell nearest the middle of the bottom edge, or with impact_width w > 0
// every cell whose centroid lies in the w × w square resting on the middle of the bottom edge (the same
// projectile on a finer mesh). All fly into the block (+y) at one speed: impact_speed, or the speed that
// gives them impact_energy.
LoadingSetup impact_kick(const Loading& loading, const mesh::CellMesh& mesh, const Bodies& bodies, std::span<double> v0,
                         double depth) {
  LoadingSetup setup;
  const std::size_t n = mesh.cells();
  const auto& b = mesh.bounds;
  const double xc = 0.5 * (b[0] + b[2]), w = loading.impact_width;
  std::size_t src = n;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& c = mesh.centroid[k];
    if (w > 0 && std::abs(c.x() - xc) < 0.5 * w && c.y() < b[1] + w) setup.kicked.push_back(k);
    if (c.y() >= b[1] + (w > 0 ? w : depth)) continue;
    if (src == n || std::abs(c.x() - xc) < std::abs(mesh.centroid[src].x() - xc)) src = k;
  }
  if (src == n)
    throw InputError("loading.kind = impact: no cell within " + std::to_string(w > 0 ? w : depth) +
                     " m of the bottom edge");
  if (setup.kicked.empty()) setup.kicked.push_back(src);
  setup.source = src;
  double mass = 0;
  for (std::size_t k : setup.kicked) mass += bodies.mass[k];
  const double speed = loading.impact_energy > 0 ? std::sqrt(2 * loading.impact_energy / mass) : loading.impact_speed;
  for (std::size_t k : setup.kicked) v0[n + k] = speed;
  setup.kinetic_energy = 0.5 * mass * speed * speed;
  return setup;
}

}  // namespace

double LoadingProbe::stress(std::span<const double> force, std::size_t n) const {
  const double ft = sum_over(top, force.data() + n), fb = sum_over(bottom, force.data() + n);
  return (fb - ft) / (2 * width0 * thickness);
}

double LoadingProbe::axial_strain(std::span<const double> q, std::size_t n) const {
  const double* y = q.data() + n;
  return (mean(top, y) - mean(bottom, y)) / length0 - 1.0;
}

double LoadingProbe::lateral_strain(std::span<const double> q, std::size_t n) const {
  (void)n;
  const double* x = q.data();
  return (mean(right, x) - mean(left, x)) / width0 - 1.0;
}

namespace {

// The uniaxial and the confined compression tests: the top and bottom layers move apart (tension) or together,
// the confined test's also held in x and in angle; the side columns measure the lateral strain.
LoadingSetup boundary_layers(const Loading& loading, const mesh::CellMesh& mesh, Model& model, double depth,
                             bool confined) {
  LoadingSetup setup;
  const std::size_t n = mesh.cells();
  const auto& b = mesh.bounds;
  LoadingProbe& p = setup.probe;
  p.active = true;
  p.thickness = model.material().thickness;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& c = mesh.centroid[k];
    if (c.y() > b[3] - depth)
      p.top.push_back(k);
    else if (c.y() < b[1] + depth)
      p.bottom.push_back(k);
    if (c.x() > b[2] - depth) p.right.push_back(k);
    if (c.x() < b[0] + depth) p.left.push_back(k);
  }
  if (p.top.empty() || p.bottom.empty() || p.left.empty() || p.right.empty())
    throw InputError("loading.kind = " + loading.name + ": the mesh has no boundary layer within " +
                     std::to_string(depth) + " m of an edge");
  std::vector<double> cx(n), cy(n);
  for (std::size_t k = 0; k < n; ++k) {
    cx[k] = mesh.centroid[k].x();
    cy[k] = mesh.centroid[k].y();
  }
  p.length0 = mean(p.top, cy.data()) - mean(p.bottom, cy.data());
  p.width0 = mean(p.right, cx.data()) - mean(p.left, cx.data());
  const double sign = loading.tension ? 1.0 : -1.0;
  const int up = model.add_layer({sign * loading.boundary_speed, loading.ramp});
  const int down = model.add_layer({-sign * loading.boundary_speed, loading.ramp});
  const int fixed = model.add_layer({0.0, loading.ramp});
  for (auto [cells, layer] : {std::pair{&p.top, up}, std::pair{&p.bottom, down}}) {
    for (std::size_t k : *cells) {
      model.add_prescribed(n + k, cy[k], layer);
      if (confined) {
        model.add_prescribed(k, cx[k], fixed);
        model.add_prescribed(2 * n + k, 0.0, fixed);
      }
    }
  }
  return setup;
}

// The keys of the layer tests; `direction` their default direction.
void read_layers(Scene& s, Loading& l, const std::string& direction) {
  l.tension = s.choice("loading.direction", direction, {"tension", "compression"}) == "tension";
  l.boundary_speed = s.in("loading.boundary_speed", l.boundary_speed, Interval::open_closed(0, limits::kSpeed));
  l.ramp = s.positive("loading.ramp", l.ramp);
  l.layer_depth = s.non_negative("loading.layer_depth", l.layer_depth);
}

LoadingRow layer_row(const std::string& name, const std::string& direction, bool confined) {
  return {name, [direction](Scene& s, Loading& l) { read_layers(s, l, direction); },
          [confined](const Loading& l, const mesh::CellMesh& m, Model& model, std::span<double>, double depth) {
            return boundary_layers(l, m, model, depth, confined);
          },
          [](const Loading&) { return std::string(); }};
}

LoadingRow kick_row(const std::string& name) {
  return {name, [](Scene& s, Loading& l) { l.energy = s.positive("loading.energy", l.energy); },
          [](const Loading& l, const mesh::CellMesh& m, Model& model, std::span<double> v0, double) {
            return explosion_kick(l, m, model.bodies(), v0);
          },
          [](const Loading& l) { return "loading.energy = " + format_value(l.energy) + " J"; }};
}

LoadingRow impact_row() {
  const auto read = [](Scene& s, Loading& l) {
    l.impact_speed = s.in("loading.impact_speed", l.impact_speed, Interval::open_closed(0, limits::kSpeed));
    l.impact_energy = s.non_negative("loading.impact_energy", l.impact_energy);
    l.impact_width = s.non_negative("loading.impact_width", l.impact_width);
    l.layer_depth = s.non_negative("loading.layer_depth", l.layer_depth);
  };
  const auto apply = [](const Loading& l, const mesh::CellMesh& m, Model& model, std::span<double> v0, double depth) {
    const double width = m.bounds[2] - m.bounds[0];
    if (!(l.impact_width <= width))
      throw UsageError("loading.impact_width = " + format_value(l.impact_width) + " m: wider than the sample (" +
                       format_value(width) + " m)");
    return impact_kick(l, m, model.bodies(), v0, depth);
  };
  const auto source = [](const Loading& l) {
    return l.impact_energy > 0 ? "loading.impact_energy = " + format_value(l.impact_energy) + " J"
                               : "loading.impact_speed = " + format_value(l.impact_speed) + " m/s";
  };
  return {"impact", read, apply, source};
}

}  // namespace

const std::vector<LoadingRow>& loading_table() {
  static const std::vector<LoadingRow> table{
      {"none", [](Scene&, Loading&) {},
       [](const Loading&, const mesh::CellMesh&, Model&, std::span<double>, double) { return LoadingSetup{}; },
       [](const Loading&) { return std::string(); }},
      layer_row("uniaxial", "tension", false),
      layer_row("confined-compression", "compression", true),
      kick_row("explosion"),
      impact_row(),
      kick_row("pulse"),
  };
  return table;
}

const LoadingRow& loading_row(const std::string& name) {
  for (const LoadingRow& row : loading_table())
    if (row.name == name) return row;
  throw std::out_of_range("no loading kind '" + name + "'");
}

LoadingSetup apply_loading(const Loading& loading, const mesh::CellMesh& mesh, Model& model, std::span<double> v0) {
  const std::size_t n = mesh.cells();
  const double g = model.bodies().length_scale;
  const double depth = loading.layer_depth > 0 ? loading.layer_depth : g;
  const auto& b = mesh.bounds;
  const double width = b[2] - b[0], height = b[3] - b[1];
  if (loading.layer_depth > 0 && !(2 * loading.layer_depth < std::min(width, height)))
    throw UsageError("loading.layer_depth = " + format_value(loading.layer_depth) +
                     " m: the boundary layers would meet (the sample is " + format_value(width) + " x " +
                     format_value(height) + " m)");
  const LoadingRow& row = loading_row(loading.name);
  LoadingSetup setup = row.apply(loading, mesh, model, v0, depth);
  // An energy far beyond the sample's (a typo, a unit slip) kicks cells faster than any solid stays one.
  double fastest = 0;
  std::size_t cell = n;
  for (std::size_t k : setup.kicked) {
    const double v = std::hypot(v0[k], v0[n + k]);
    if (!(v <= fastest)) fastest = v, cell = k;
  }
  if (!(fastest <= limits::kSpeed))
    throw UsageError(row.kick_source(loading) + ": kicks cell " + std::to_string(cell) + " to " +
                     format_value(fastest) + " m/s, above the " + format_value(limits::kSpeed) +
                     " m/s any solid of this model survives as one");
  return setup;
}

}  // namespace frac::dem
