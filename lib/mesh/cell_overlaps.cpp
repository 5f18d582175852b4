#include "mesh/cell_overlaps.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>

#include "geometry/overlap.hpp"
#include "geometry/separation.hpp"

namespace frac::mesh {
namespace {

// Candidate pairs looked at per cell before the cells count as too unequal in size to check in linear time.
// The meshes of mesh-gen voronoi look at 8 (disorder 0) to 40 (--disorder-region disc) per cell.
constexpr std::size_t kPairsPerCell = 128;

// x rounded down to a whole number in [0, most]; 0 for NaN (a mesh of absurd extent gets one bucket, and the
// search then stops at its budget).
std::int64_t whole(double x, std::int64_t most) {
  if (!(x >= 1)) return 0;
  return x >= static_cast<double>(most) ? most : static_cast<std::int64_t>(x);
}

// The cells' centroids sorted into square buckets (a counting sort: O(N)).
class CentroidGrid {
 public:
  // Buckets of side at least h, at most about 4 N of them (a wider bucket only adds candidates).
  CentroidGrid(std::span<const Vec2> c, double h) {
    Vec2 hi = c[0];
    lo_ = c[0];
    for (const Vec2& p : c) lo_ = lo_.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec2 extent = hi - lo_;
    const double most = 4.0 * static_cast<double>(c.size()) + 16.0;
    while ((extent.x() / h + 1) * (extent.y() / h + 1) > most) h *= 2;
    h_ = h;
    const auto limit = static_cast<std::int64_t>(most);
    nx_ = whole(extent.x() / h, limit) + 1;
    ny_ = whole(extent.y() / h, limit / nx_) + 1;
    start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
    for (const Vec2& p : c) ++start_[bucket(p) + 1];
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    cell_.resize(c.size());
    for (std::size_t k = 0; k < c.size(); ++k) cell_[next[bucket(c[k])]++] = k;
  }
  double side() const { return h_; }
  // Calls f(j) for every cell j in the buckets within `reach` of p along x and y.
  template <class F>
  void near(const Vec2& p, double reach, F&& f) const {
    const std::int64_t i0 = column(p.x() - reach), i1 = column(p.x() + reach);
    const std::int64_t j0 = row(p.y() - reach), j1 = row(p.y() + reach);
    for (std::int64_t j = j0; j <= j1; ++j)
      for (std::int64_t i = i0; i <= i1; ++i) {
        const auto b = static_cast<std::size_t>(j * nx_ + i);
        for (std::size_t k = start_[b]; k < start_[b + 1]; ++k) f(cell_[k]);
      }
  }

 private:
  std::int64_t index(double offset, std::int64_t count) const { return whole(offset / h_, count - 1); }
  std::int64_t column(double x) const { return index(x - lo_.x(), nx_); }
  std::int64_t row(double y) const { return index(y - lo_.y(), ny_); }
  std::size_t bucket(const Vec2& p) const { return static_cast<std::size_t>(row(p.y()) * nx_ + column(p.x())); }
  Vec2 lo_;
  double h_ = 1.0;
  std::int64_t nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_, cell_;
};

// Whether an edge of p or of q separates the two convex polygons, allowing a penetration of `slack`; the edges
// facing the other polygon (along d, from p's centroid to q's) first: for cells that share a side, they do.
bool separated(std::span<const Vec2> p, std::span<const Vec2> q, const Vec2& d, double slack) {
  if (geometry::edge_separates(p, geometry::facing_edge(p, d), q, slack) ||
      geometry::edge_separates(q, geometry::facing_edge(q, -d), p, slack))
    return true;
  for (std::size_t e = 0; e < p.size(); ++e)
    if (geometry::edge_separates(p, e, q, slack)) return true;
  for (std::size_t e = 0; e < q.size(); ++e)
    if (geometry::edge_separates(q, e, p, slack)) return true;
  return false;
}

// The farthest vertex of each cell from its centroid.
std::vector<double> reaches(const CellMesh& m) {
  std::vector<double> r(m.cells(), 0.0);
  for (std::size_t k = 0; k < r.size(); ++k)
    for (const Vec2& v : m.polygon(k)) r[k] = std::max(r[k], v.norm());
  return r;
}

class Search {
 public:
  Search(const CellMesh& m, double slack, double g, std::size_t most)
      : m_(m), slack_(slack), g_(g), most_(most), reach_(reaches(m)) {}

  OverlapSearch run() {
    const std::size_t n = m_.cells();
    // Buckets fit the cells up to 4 times the median reach, so that a few wide cells do not widen them all.
    std::vector<double> sorted = reach_;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2), sorted.end());
    cap_ = std::min(*std::max_element(reach_.begin(), reach_.end()), 4 * sorted[n / 2]);
    if (!(cap_ > 0)) return out_;  // (degenerate polygons fail the other invariants)
    const CentroidGrid grid(m_.centroid, 2 * cap_);
    budget_ = kPairsPerCell * n;
    std::vector<std::size_t> wide;
    for (std::size_t i = 0; i < n && going(); ++i) {
      if (reach_[i] > cap_) {
        wide.push_back(i);
        continue;
      }
      grid.near(m_.centroid[i], grid.side(), [&](std::size_t j) {
        if (j > i && reach_[j] <= cap_) test(i, j);
      });
    }
    // A wide cell looks at every narrow cell within its reach, and at every other wide cell.
    for (std::size_t w = 0; w < wide.size() && going(); ++w) {
      const std::size_t i = wide[w];
      grid.near(m_.centroid[i], reach_[i] + cap_, [&](std::size_t j) {
        if (reach_[j] <= cap_) test(i, j);
      });
      for (std::size_t v = w + 1; v < wide.size() && going(); ++v) test(i, wide[v]);
    }
    if (out_.pairs > budget_) {
      out_.complete = false;
      out_.widest = static_cast<std::size_t>(std::max_element(reach_.begin(), reach_.end()) - reach_.begin());
    }
    std::sort(out_.found.begin(), out_.found.end(),
              [](const CellOverlap& x, const CellOverlap& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    return out_;
  }

 private:
  bool going() const { return out_.pairs <= budget_ && out_.found.size() < most_; }

  void test(std::size_t i, std::size_t j) {
    ++out_.pairs;
    const Vec2 d = m_.centroid[j] - m_.centroid[i];
    const double apart = reach_[i] + reach_[j] + slack_;
    if (!(d.squaredNorm() < apart * apart) || out_.found.size() >= most_) return;
    // In i's body frame: j moved by d.
    const auto p = m_.polygon(i);
    q_.clear();
    for (const Vec2& v : m_.polygon(j)) q_.push_back(v + d);
    if (separated(p, q_, d, slack_)) return;
    const double area = area_of(p, q_, d);
    if (!(area <= 0)) out_.found.push_back({std::min(i, j), std::max(i, j), area});
  }

  // The intersection's area (0 below geometry's tolerance, a touch); NaN beyond its vertex limit.
  double area_of(std::span<const Vec2> p, std::span<const Vec2> q, const Vec2& d) const {
    if (p.size() > geometry::kMaxContactPolygonVertices || q.size() > geometry::kMaxContactPolygonVertices)
      return std::numeric_limits<double>::quiet_NaN();
    return geometry::convex_overlap(p, q, Vec2::Zero(), d, g_).area;
  }

  const CellMesh& m_;
  double slack_, g_;
  std::size_t most_;
  std::vector<double> reach_;
  double cap_ = 0.0;
  std::size_t budget_ = 0;
  std::vector<Vec2> q_;
  OverlapSearch out_;
};

}  // namespace

OverlapSearch find_cell_overlaps(const CellMesh& m, double slack, double length_scale, std::size_t most) {
  if (m.cells() < 2 || most == 0) return {};
  return Search(m, slack, length_scale, most).run();
}

}  // namespace frac::mesh
