#include "mesh/random_lattice.hpp"

#include <cmath>
#include <limits>
#include <new>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "mesh/voronoi.hpp"

namespace frac::mesh {
namespace {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

void validate(const RandomLatticeOptions& opt) {
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (opt.shape != "rect" && opt.shape != "disc") {
    throw UsageError("--shape: must be 'rect' or 'disc', got '" + opt.shape + "'");
  }
  if (opt.shape == "rect") {
    if (!positive(opt.width) || !positive(opt.height)) {
      throw UsageError("--size: width and height must be positive and finite, got " + fmt(opt.width) + " x " +
                       fmt(opt.height));
    }
    if (opt.nx < 1 || opt.ny < 1) {
      throw UsageError("--cells: need at least 1 x 1 grid cells, got " + std::to_string(opt.nx) + " x " +
                       std::to_string(opt.ny));
    }
    if (opt.nx > std::numeric_limits<std::int32_t>::max() / opt.ny) {
      throw UsageError("--cells: too many grid cells");
    }
    const double gx = opt.width / static_cast<double>(opt.nx), gy = opt.height / static_cast<double>(opt.ny);
    if (std::abs(gx - gy) > 1e-9 * gx) {
      throw UsageError("--size/--cells: grid cells must be square, but width/nx = " + fmt(gx) +
                       " m and height/ny = " + fmt(gy) + " m");
    }
  } else {
    if (!positive(opt.diameter)) throw UsageError("--diameter: must be positive and finite, got " + fmt(opt.diameter));
    if (opt.cells < 1) throw UsageError("--cells: need at least 1 cell, got " + std::to_string(opt.cells));
    if (opt.cells > std::numeric_limits<std::int32_t>::max() / 2) throw UsageError("--cells: too many cells");
  }
  if (!(opt.disorder >= 0.0 && opt.disorder <= 1.0)) {
    throw UsageError("--disorder: must lie in [0, 1], got " + fmt(opt.disorder));
  }
  if (opt.disorder_region != "square" && opt.disorder_region != "disc") {
    throw UsageError("--disorder-region: must be 'square' or 'disc', got '" + opt.disorder_region + "'");
  }
  if (!(opt.min_section >= 0.0 && opt.min_section < 1.0)) {
    throw UsageError("--min-section: must lie in [0, 1) (a fraction of the spacing), got " + fmt(opt.min_section));
  }
}

// A square grid of sites: cell (i, j), i < n_x, j < n_y, has its centre at origin + ((i + 1/2) g, (j + 1/2) g_y)
// (g_y = g up to 1e-9 relative: height / ny for a rectangle, so the top row ends exactly at the box)
// and its site at the centre plus a random offset; sites are listed in grid order (index j n_x + i).
// Offsets: uniform in [-a/2, a/2]^2 ("square") or uniform in the disc of radius a ("disc", by
// rejection from the square [-a, a]^2, which keeps the draws portable), a = disorder * g. Two
// uniforms per accepted draw, x first. A site that lands outside `box` (possible only with the disc
// region, a > g/2, in a boundary cell) is mirrored back into it across the side it crossed, which
// keeps one site per boundary cell and the density uniform up to the mirror.
std::vector<geometry::Vec2> throw_sites(std::int64_t n_x, std::int64_t n_y, double g, double g_y,
                                        const geometry::Vec2& origin, const RandomLatticeOptions& opt,
                                        const std::array<double, 4>& box) {
  Rng rng(opt.seed);
  const double a = opt.disorder * g;
  const bool disc = opt.disorder_region == "disc";
  std::vector<geometry::Vec2> sites;
  sites.reserve(static_cast<std::size_t>(n_x * n_y));
  for (std::int64_t j = 0; j < n_y; ++j) {
    for (std::int64_t i = 0; i < n_x; ++i) {
      double dx = 0.0, dy = 0.0;
      if (a > 0.0) {
        if (disc) {
          do {
            dx = rng.uniform(-1.0, 1.0);
            dy = rng.uniform(-1.0, 1.0);
          } while (dx * dx + dy * dy >= 1.0);
          dx *= a;
          dy *= a;
        } else {
          dx = rng.uniform(-0.5 * a, 0.5 * a);
          dy = rng.uniform(-0.5 * a, 0.5 * a);
        }
      }
      double x = origin.x() + (static_cast<double>(i) + 0.5) * g + dx;
      double y = origin.y() + (static_cast<double>(j) + 0.5) * g_y + dy;
      if (x < box[0]) x = 2.0 * box[0] - x;
      if (x > box[2]) x = 2.0 * box[2] - x;
      if (y < box[1]) y = 2.0 * box[1] - y;
      if (y > box[3]) y = 2.0 * box[3] - y;
      sites.emplace_back(x, y);
    }
  }
  return sites;
}

// The grid the sites are thrown on: n_x × n_y cells of size g (g_y upright) from `origin`, and the box
// the Voronoi cells are clipped to.
struct SiteGrid {
  std::int64_t n_x = 0, n_y = 0;
  double g = 0.0, g_y = 0.0, radius = 0.0;  // radius: of the disc (0 for a rectangle)
  geometry::Vec2 origin;
  std::array<double, 4> box{};
};

// The grid of a rectangle (the box itself), or of a disc of radius R: centred on the origin and covering
// [-R - 4g, R + 4g]^2, with g the side of a square of the disc's area per cell. A margin of 3g suffices
// for the square region (a kept cell has its vertices within 2 sqrt(2) g of its centroid, so it never
// touches the box); 4g also covers the disc region with a = g (empty circles of radius < (1 + 1/sqrt(2)) g).
// Sets the mesh's bounds.
SiteGrid site_grid(const RandomLatticeOptions& opt, CellMesh& m) {
  SiteGrid s;
  if (opt.shape == "rect") {
    s.n_x = opt.nx;
    s.n_y = opt.ny;
    s.g = opt.width / static_cast<double>(opt.nx);
    s.g_y = opt.height / static_cast<double>(opt.ny);
    s.origin = geometry::Vec2(0.0, 0.0);
    s.box = {0.0, 0.0, opt.width, opt.height};
    m.bounds = s.box;
  } else {
    s.radius = 0.5 * opt.diameter;
    s.g = std::sqrt(std::numbers::pi * s.radius * s.radius / static_cast<double>(opt.cells));
    s.g_y = s.g;
    s.n_x = s.n_y = static_cast<std::int64_t>(std::ceil(2.0 * (s.radius + 4.0 * s.g) / s.g));
    const double half = 0.5 * static_cast<double>(s.n_x) * s.g;
    s.origin = geometry::Vec2(-half, -half);
    s.box = {-half, -half, half, half};
    m.bounds = {-s.radius, -s.radius, s.radius, s.radius};
  }
  return s;
}

// The Voronoi cells kept as the mesh's cells (world vertices and centroids), in grid order: all of them for
// a rectangle, the ones whose centroid lies within R for a disc. Returns new_index: a kept site's cell
// index, -1 for a dropped site.
std::vector<std::int64_t> keep_cells(FlatVoronoiDiagram& vd, const RandomLatticeOptions& opt, double radius,
                                     CellMesh& m) {
  const std::size_t n = vd.offset.size() - 1;
  auto world = [&vd](std::size_t k) {
    return std::span<const geometry::Vec2>(vd.vertex.data() + vd.offset[k],
                                           static_cast<std::size_t>(vd.offset[k + 1] - vd.offset[k]));
  };
  std::vector<std::int64_t> new_index(n, -1);
  std::vector<geometry::Vec2> c(n);
  std::int64_t kept = 0;
  std::size_t total_vertices = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto poly = world(k);
    if (poly.size() < 3) {
      if (opt.shape == "rect") throw RuntimeError("make_random_lattice: empty Voronoi cell in the box");
      continue;
    }
    c[k] = geometry::centroid(poly);
    if (opt.shape == "disc" && c[k].norm() > radius) continue;
    new_index[k] = kept++;
    total_vertices += poly.size();
  }
  if (kept == 0) throw UsageError("--cells: the disc holds no whole cell; ask for more cells");

  const auto cells = static_cast<std::size_t>(kept);
  if (cells == n) {
    // Every cell kept (a rectangle): take the flat arrays over (shifted to body frames in place later).
    m.vertex_offset = std::move(vd.offset);
    m.vertex = std::move(vd.vertex);
    m.centroid = std::move(c);
  } else {
    m.vertex_offset.reserve(cells + 1);
    m.vertex.reserve(total_vertices);
    m.centroid.reserve(cells);
    for (std::size_t k = 0; k < n; ++k) {
      if (new_index[k] < 0) continue;
      const auto poly = world(k);
      m.vertex.insert(m.vertex.end(), poly.begin(), poly.end());
      m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
      m.centroid.push_back(c[k]);
    }
  }
  return new_index;
}

// Each cell's vertices about its centroid (the body frame), its area and polar second moment.
void to_body_frames(CellMesh& m) {
  const std::size_t cells = m.centroid.size();
  m.area.resize(cells);
  m.second_moment.resize(cells);
  for (std::size_t k = 0; k < cells; ++k) {
    const auto first = static_cast<std::size_t>(m.vertex_offset[k]);
    const auto count = static_cast<std::size_t>(m.vertex_offset[k + 1]) - first;
    for (std::size_t i = first; i < first + count; ++i) m.vertex[i] -= m.centroid[k];
    const std::span<const geometry::Vec2> body(m.vertex.data() + first, count);
    m.area[k] = geometry::signed_area(body);
    m.second_moment[k] = geometry::polar_second_moment(body);
  }
}

// Beams between kept neighbours whose shared side is positive and at least min_side. Neighbour pairs come
// sorted (a < b) from voronoi_in_box and the renumbering keeps the order.
void add_beams(const FlatVoronoiDiagram& vd, const std::vector<std::int64_t>& new_index, double min_side, CellMesh& m) {
  m.beam.reserve(vd.neighbour.size());
  m.beam_length.reserve(vd.neighbour.size());
  m.beam_section.reserve(vd.neighbour.size());
  for (std::size_t e = 0; e < vd.neighbour.size(); ++e) {
    const auto a = new_index[static_cast<std::size_t>(vd.neighbour[e][0])];
    const auto b = new_index[static_cast<std::size_t>(vd.neighbour[e][1])];
    if (a < 0 || b < 0 || vd.shared_side[e] < min_side || vd.shared_side[e] <= 0.0) continue;
    m.beam.push_back({a, b});
    m.beam_length.push_back((m.centroid[static_cast<std::size_t>(b)] - m.centroid[static_cast<std::size_t>(a)]).norm());
    m.beam_section.push_back(vd.shared_side[e]);
  }
}

}  // namespace

void refuse_ignored_options(const RandomLatticeOptions& opt, const std::set<std::string>& given) {
  const auto refuse = [&](const std::string& option, bool ignored, const std::string& why) {
    if (ignored && given.count(option)) throw UsageError("--" + option + ": " + why);
  };
  refuse("size", opt.shape == "disc", "applies to --shape rect; a disc takes --diameter");
  refuse("diameter", opt.shape == "rect", "applies to --shape disc; a rectangle takes --size");
}

CellMesh make_random_lattice(const RandomLatticeOptions& opt) try {
  validate(opt);
  CellMesh m;
  m.shape = opt.shape;
  m.disorder = opt.disorder;
  m.disorder_region = opt.disorder_region;
  const SiteGrid grid = site_grid(opt, m);
  const double g = grid.g;
  m.spacing = g;

  const std::vector<geometry::Vec2> sites = throw_sites(grid.n_x, grid.n_y, g, grid.g_y, grid.origin, opt, grid.box);
  // Merge Voronoi vertices closer than 1e-9 g: at disorder 0 the four sites around a grid vertex are
  // cocircular and the two triangles' circumcenters differ only by round-off (~1e-16 of the coordinates).
  FlatVoronoiDiagram vd = voronoi_in_box_flat(sites, grid.box, 1e-9 * g);
  const std::vector<std::int64_t> new_index = keep_cells(vd, opt, grid.radius, m);
  to_body_frames(m);
  add_beams(vd, new_index, opt.min_section * g, m);
  return m;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the Voronoi mesh of " + std::to_string(opt.shape == "disc" ? opt.cells : opt.nx * opt.ny) +
                      " cells");
}

}  // namespace frac::mesh
