// Voronoi cells clipped to a box, from CGAL's Delaunay triangulation. The one translation unit of the
// project that includes CGAL (about 8 s and 0.8 GB to compile): keep everything else out of it.
#include "mesh/voronoi.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace frac::mesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int64_t, K>;  // site index, -1 for dummies
using Fb = CGAL::Triangulation_face_base_with_info_2<std::int64_t, K>;    // index of the circumcenter
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;

using geometry::Polygon;
using geometry::Vec2;

bool outside(const Vec2& p, const std::array<double, 4>& box) {
  return p.x() < box[0] || p.y() < box[1] || p.x() > box[2] || p.y() > box[3];
}

// Length of the part of segment p-q inside the box (Liang-Barsky).
double clipped_length(const Vec2& p, const Vec2& q, const std::array<double, 4>& box) {
  const Vec2 d = q - p;
  double t0 = 0.0, t1 = 1.0;
  // Constraint: num + t * den >= 0 for each of the four sides.
  const double num[4] = {p.x() - box[0], box[2] - p.x(), p.y() - box[1], box[3] - p.y()};
  const double den[4] = {d.x(), -d.x(), d.y(), -d.y()};
  for (int k = 0; k < 4; ++k) {
    if (den[k] == 0.0) {
      if (num[k] < 0.0) return 0.0;  // parallel to this side and outside it
      continue;
    }
    const double t = -num[k] / den[k];
    if (den[k] > 0.0) {
      t0 = std::max(t0, t);  // entering
    } else {
      t1 = std::min(t1, t);  // leaving
    }
    if (t0 >= t1) return 0.0;
  }
  return (t1 - t0) * d.norm();
}

// Remove vertices closer than tol to the previous kept vertex (and the last ones closer than tol to
// the first), in place.
void drop_near_repeats(Polygon& poly, double tol) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    if (kept == 0 || (poly[k] - poly[kept - 1]).norm() > tol) poly[kept++] = poly[k];
  }
  while (kept > 1 && (poly[kept - 1] - poly[0]).norm() <= tol) --kept;
  poly.resize(kept);
}

// Circumcenter of a counter-clockwise triangle, computed relative to its lexicographically smallest
// vertex with the others in counter-clockwise order: the rounding then does not depend on which
// vertex CGAL stores first in the face (which follows the insertion order, i.e. the spatial sort).
Vec2 canonical_circumcenter(const Point& p0, const Point& p1, const Point& p2) {
  auto less = [](const Point& a, const Point& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); };
  const Point* v[3] = {&p0, &p1, &p2};
  int first = 0;
  if (less(*v[1], *v[first])) first = 1;
  if (less(*v[2], *v[first])) first = 2;
  const Point& a = *v[first];
  const Point& b = *v[(first + 1) % 3];
  const Point& c = *v[(first + 2) % 3];
  const double bx = b.x() - a.x(), by = b.y() - a.y(), cx = c.x() - a.x(), cy = c.y() - a.y();
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double den = 2.0 * (bx * cy - by * cx);
  return Vec2(a.x() + (cy * b2 - by * c2) / den, a.y() + (bx * c2 - cx * b2) / den);
}

// Rotate so that the polygon starts at its lowest vertex (then leftmost): the output does not depend
// on where CGAL's circulator happened to start.
void rotate_to_canonical_start(Polygon& poly) {
  if (poly.empty()) return;
  const auto lowest = std::min_element(poly.begin(), poly.end(), [](const Vec2& a, const Vec2& b) {
    return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x());
  });
  std::rotate(poly.begin(), lowest, poly.end());
}

// The Delaunay triangulation of the sites (info: site index) plus four far dummies (info -1) at the corners
// of a square of half-side 3 d around the box centre (d = box diagonal). Every site inside that square is
// strictly inside the convex hull, so its cell is bounded. A box point is at most d from any site in the
// box and more than 3.7 d from a dummy, so as long as one site lies in the box no dummy cell reaches into
// the box.
void triangulate_with_dummies(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box, Delaunay& dt) {
  const std::size_t n = sites.size();
  const double width = box[2] - box[0], height = box[3] - box[1];
  std::vector<std::pair<Point, std::int64_t>> points;
  points.reserve(n + 4);
  for (std::size_t k = 0; k < n; ++k) {
    points.emplace_back(Point(sites[k].x(), sites[k].y()), static_cast<std::int64_t>(k));
  }
  const double cx = 0.5 * (box[0] + box[2]), cy = 0.5 * (box[1] + box[3]);
  const double far = 3.0 * std::hypot(width, height);
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) points.emplace_back(Point(cx + sx * far, cy + sy * far), -1);
  }
  dt.insert(points.begin(), points.end());  // spatially sorted bulk insertion
  if (dt.number_of_vertices() != n + 4) {
    throw std::invalid_argument("voronoi_in_box: sites must be distinct");
  }
}

// Circumcenter of every finite face, computed once (face info = its index; -1 until computed).
// Delaunay faces are never flat (exact predicates), so the denominator is not zero.
//
// Voronoi vertices closer than merge_tol are merged here, once for all cells: faces joined by a
// Delaunay edge whose Voronoi edge is that short form clusters (union-find), and every face of a
// cluster takes the cluster's mean circumcenter. Merging per cell instead would drop a vertex in
// one cell and keep it in the next, leaving slivers of gap (the total area then falls short by
// ~1e-10 relative at disorder ~1e-9). With shared points the cells tile the box to round-off and a
// collapsed side simply repeats a point. Each edge is tested once, when its second face is reached.
std::vector<Vec2> merged_circumcenters(Delaunay& dt, double merge_tol) {
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) f->info() = -1;
  std::vector<Vec2> center;
  center.reserve(dt.number_of_faces());
  const double tol2 = merge_tol * merge_tol;
  std::vector<std::int64_t> parent;  // union-find over faces, allocated at the first merge
  auto root = [&parent](std::int64_t x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      const auto up = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      parent[static_cast<std::size_t>(x)] = up;  // path halving
      x = up;
    }
    return x;
  };
  const std::size_t faces = dt.number_of_faces();
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const auto a = static_cast<std::int64_t>(center.size());
    f->info() = a;
    center.push_back(canonical_circumcenter(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
    if (merge_tol <= 0.0) continue;
    for (int i = 0; i < 3; ++i) {
      const std::int64_t b = f->neighbor(i)->info();  // -1: infinite or not reached yet
      if (b < 0 || (center.back() - center[static_cast<std::size_t>(b)]).squaredNorm() > tol2) continue;
      if (parent.empty()) {
        parent.resize(faces);
        for (std::size_t k = 0; k < faces; ++k) parent[k] = static_cast<std::int64_t>(k);
      }
      const auto ra = root(a), rb = root(b);
      if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  if (!parent.empty()) {
    std::vector<Vec2> sum(center.size(), Vec2::Zero());
    std::vector<std::int32_t> count(center.size(), 0);
    for (std::size_t i = 0; i < center.size(); ++i) {
      const auto r = static_cast<std::size_t>(root(static_cast<std::int64_t>(i)));
      sum[r] += center[i];
      ++count[r];
    }
    for (std::size_t i = 0; i < center.size(); ++i) {
      const auto r = static_cast<std::size_t>(root(static_cast<std::int64_t>(i)));
      if (count[r] > 1) center[i] = sum[r] / static_cast<double>(count[r]);
    }
  }
  return center;
}

// A side of a cell toward a neighbour of higher index in the box.
struct Side {
  std::int64_t neighbour;  // > k
  std::size_t first;       // the side runs from ring[first] to ring[first + 1]
  double length;           // inside the box
};

// A site's cell and pairs, gathered in CGAL's memory order: its stretch of the vertices and of the pairs.
struct Block {
  std::size_t vertex = 0, pair = 0;  // starts in polys and pending
  std::uint8_t vertices = 0, pairs = 0;
};

// The cells as the sites are visited, before they are gathered in site order.
struct CellBlocks {
  std::vector<Vec2> polys;
  std::vector<std::pair<std::int64_t, double>> pending;  // (neighbour, side length)
  std::vector<Block> block;
};

// The Voronoi vertices around site v, counter-clockwise, into `ring`: the circumcenters of its faces. Face
// f_j = (site, a, b) counter-clockwise is followed by the face across its edge site-b, so the side from
// center(f_j) to center(f_j+1) is the one shared with b = f_j->vertex(cw(index of the site in f_j)). The
// sides toward neighbours of higher index in the box go to `across`. Returns whether a vertex lies outside
// the box (the cell needs clipping).
bool ring_around(const Delaunay& dt, Delaunay::Vertex_handle v, std::size_t k, const std::vector<Vec2>& center,
                 const std::array<double, 4>& box, const std::vector<char>& in_box, Polygon& ring,
                 std::vector<Side>& across) {
  ring.clear();
  across.clear();
  bool needs_clip = false;
  auto fc = dt.incident_faces(v);
  const auto done = fc;
  do {
    if (dt.is_infinite(fc)) {
      // Cannot happen for a site inside the box (it is strictly inside the dummies' hull).
      throw std::logic_error("voronoi_in_box: unbounded cell for a site inside the box");
    }
    const Vec2& c = center[static_cast<std::size_t>(fc->info())];
    needs_clip = needs_clip || outside(c, box);
    ring.push_back(c);
    const std::int64_t j = fc->vertex(Delaunay::cw(fc->index(v)))->info();
    if (j > static_cast<std::int64_t>(k) && in_box[static_cast<std::size_t>(j)]) {
      across.push_back({j, ring.size() - 1, 0.0});
    }
  } while (++fc != done);
  return needs_clip;
}

// Per cell in the box: its vertices and its pairs with neighbours of higher index (each neighbour pair is
// recorded once, from its lower index). The sites are visited in CGAL's memory order (spatially sorted:
// far fewer cache misses than site order); each site's vertices and pairs go to a block of `polys` and
// `pending`, and the blocks are gathered in site order at the end, which also lists the pairs sorted
// without a sort.
CellBlocks cells_in_box(const Delaunay& dt, const std::vector<Vec2>& center, std::span<const geometry::Vec2> sites,
                        const std::array<double, 4>& box, double merge_tol) {
  const std::size_t n = sites.size();
  const Polygon box_poly{Vec2(box[0], box[1]), Vec2(box[2], box[1]), Vec2(box[2], box[3]), Vec2(box[0], box[3])};
  std::vector<char> in_box(n);
  for (std::size_t k = 0; k < n; ++k) in_box[k] = !outside(sites[k], box);
  Polygon ring, clipped;  // reused buffers
  std::vector<Side> across;
  CellBlocks cb;
  cb.polys.reserve(6 * n + 16);
  cb.pending.reserve(3 * n + 16);
  cb.block.resize(n);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (v->info() < 0) continue;  // dummy
    const auto k = static_cast<std::size_t>(v->info());
    if (!in_box[k]) continue;
    const bool needs_clip = ring_around(dt, v, k, center, box, in_box, ring, across);

    // Neighbours: length of the Voronoi edge inside the box.
    const std::size_t m = ring.size();
    for (auto& side : across) {
      const Vec2& p = ring[side.first];
      const Vec2& q = ring[(side.first + 1) % m];
      side.length = (needs_clip && (outside(p, box) || outside(q, box))) ? clipped_length(p, q, box) : (q - p).norm();
    }
    std::sort(across.begin(), across.end(), [](const Side& a, const Side& b) { return a.neighbour < b.neighbour; });
    Block& bk = cb.block[k];
    bk.pair = cb.pending.size();
    for (const auto& side : across) {
      if (side.length > merge_tol) cb.pending.emplace_back(side.neighbour, side.length);
    }

    // Merged vertices repeat exactly: drop the repeats. Clipping creates new points on the box sides,
    // which can fall within round-off of a vertex: drop those near-repeats (within merge_tol), but
    // nothing else (simplify's collinear test with merge_tol would also cut real corners next to
    // short sides, and open gaps between cells).
    Polygon* cell = &ring;
    if (needs_clip) {
      clipped = geometry::clip_convex(ring, box_poly, 0.0);
      drop_near_repeats(clipped, merge_tol);
      cell = &clipped;
    } else {
      drop_near_repeats(ring, 0.0);
    }
    if (cell->size() < 3) cell->clear();
    rotate_to_canonical_start(*cell);
    bk.vertex = cb.polys.size();
    cb.polys.insert(cb.polys.end(), cell->begin(), cell->end());
    if (cell->size() > 255 || cb.pending.size() - bk.pair > 255) {
      throw std::logic_error("voronoi_in_box: a cell with more than 255 vertices or neighbours");
    }
    bk.vertices = static_cast<std::uint8_t>(cell->size());
    bk.pairs = static_cast<std::uint8_t>(cb.pending.size() - bk.pair);
  }
  return cb;
}

// The blocks gathered in site order into `out` (offsets already sized n + 1).
void gather_in_site_order(const CellBlocks& cb, std::size_t n, FlatVoronoiDiagram& out) {
  std::size_t total_vertices = 0, total_pairs = 0;
  for (std::size_t k = 0; k < n; ++k) {
    total_vertices += cb.block[k].vertices;
    total_pairs += cb.block[k].pairs;
    out.offset[k + 1] = static_cast<std::int64_t>(total_vertices);
  }
  out.vertex.resize(total_vertices);
  out.neighbour.reserve(total_pairs);
  out.shared_side.reserve(total_pairs);
  for (std::size_t k = 0; k < n; ++k) {
    const Block& bk = cb.block[k];
    std::copy_n(cb.polys.begin() + static_cast<std::ptrdiff_t>(bk.vertex), bk.vertices,
                out.vertex.begin() + out.offset[k]);
    for (std::size_t e = bk.pair; e < bk.pair + bk.pairs; ++e) {
      out.neighbour.push_back({static_cast<std::int64_t>(k), cb.pending[e].first});
      out.shared_side.push_back(cb.pending[e].second);
    }
  }
}

}  // namespace

FlatVoronoiDiagram voronoi_in_box_flat(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box,
                                       double merge_tol) {
  const double width = box[2] - box[0], height = box[3] - box[1];
  if (!(width > 0.0) || !(height > 0.0) || !std::isfinite(width) || !std::isfinite(height)) {
    throw std::invalid_argument("voronoi_in_box: empty or non-finite box");
  }
  const std::size_t n = sites.size();
  FlatVoronoiDiagram out;
  out.offset.assign(n + 1, 0);
  if (n == 0) return out;
  Delaunay dt;
  triangulate_with_dummies(sites, box, dt);
  const std::vector<Vec2> center = merged_circumcenters(dt, merge_tol);
  const CellBlocks cb = cells_in_box(dt, center, sites, box, merge_tol);
  gather_in_site_order(cb, n, out);
  return out;
}

VoronoiDiagram voronoi_in_box(std::span<const geometry::Vec2> sites, const std::array<double, 4>& box,
                              double merge_tol) {
  FlatVoronoiDiagram flat = voronoi_in_box_flat(sites, box, merge_tol);
  VoronoiDiagram out;
  out.cell.resize(sites.size());
  for (std::size_t k = 0; k < sites.size(); ++k) {
    out.cell[k].assign(flat.vertex.begin() + flat.offset[k], flat.vertex.begin() + flat.offset[k + 1]);
  }
  out.neighbour = std::move(flat.neighbour);
  out.shared_side = std::move(flat.shared_side);
  return out;
}

}  // namespace frac::mesh
