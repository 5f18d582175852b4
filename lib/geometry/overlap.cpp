#include "geometry/overlap.hpp"

#include <limits>

#include <cmath>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace frac::geometry {
namespace {

// The clipper's working polygon: vertex k and the label of its edge k -> k+1, which names the
// original edge the edge lies on: 0..n-1 an edge of P_i, n + b edge b of P_j.
struct LabelledPolygon {
  std::array<Vec2, kMaxOverlapVertices> v;
  std::array<int, kMaxOverlapVertices> label;
  std::size_t size = 0;

  void push(const Vec2& p, int edge) {
    // Cannot happen for convex input within the vertex limit: each clip adds at most one vertex
    // except where round-off makes vertices alternate in and out along the clip line.
    if (size == kMaxOverlapVertices) throw RuntimeError("convex_overlap: overlap polygon exceeds its capacity");
    v[size] = p;
    label[size] = edge;
    ++size;
  }
};

// One Sutherland-Hodgman step: keep the part of `in` on the left of the directed line a -> b
// (closed half-plane, no tolerance). The new edge along the line gets `line_label`; pieces of old
// edges keep theirs. An inside vertex exactly on the line is not repeated as a crossing.
// Returns false, leaving `out` untouched, when every vertex of `in` is on the left or on the line:
// the step would copy `in` unchanged.
bool clip_step(const LabelledPolygon& in, const Vec2& a, const Vec2& b, int line_label, LabelledPolygon& out) {
  const Vec2 d = b - a;
  const std::size_t n = in.size;
  std::array<double, kMaxOverlapVertices> side;  // cross(d, p - a): > 0 on the left
  bool all_inside = true;
  for (std::size_t k = 0; k < n; ++k) {
    side[k] = cross(d, in.v[k] - a);
    all_inside = all_inside && side[k] >= 0.0;
  }
  if (all_inside) return false;
  out.size = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = k + 1 == n ? 0 : k + 1;
    const double sp = side[k], sq = side[k1];
    const Vec2& p = in.v[k];
    const Vec2& q = in.v[k1];
    if (sp >= 0.0) {
      out.push(p, in.label[k]);
      if (sq < 0.0) {
        // Leaving: from here the boundary of the result runs along the clip line.
        if (sp > 0.0) {
          out.push(p + (sp / (sp - sq)) * (q - p), line_label);
        } else {
          out.label[out.size - 1] = line_label;
        }
      }
    } else if (sq > 0.0) {
      // Entering: the rest of edge pq is a piece of the old edge. (sq == 0: q itself comes next.)
      out.push(p + (sp / (sp - sq)) * (q - p), in.label[k]);
    }
  }
  return true;
}

// The edges of a polygon as the shared-edge test needs them: d_c = p_{c+1} − p_c and tol²·|d_c|².
struct EdgeTable {
  std::array<Vec2, kMaxContactPolygonVertices> d;
  std::array<double, kMaxContactPolygonVertices> limit;
  std::span<const Vec2> p;
  EdgeTable(std::span<const Vec2> polygon, double tol2) : p(polygon) {
    const std::size_t m = p.size();
    for (std::size_t c = 0; c < m; ++c) {
      d[c] = p[c + 1 == m ? 0 : c + 1] - p[c];
      limit[c] = tol2 * d[c].squaredNorm();
    }
  }
};

// Edge u -> v of the overlap lies on the boundary of `other` too (u, v within tol of one of its
// edge lines, same orientation), or is shorter than tol: it then belongs to neither boundary.
// Distances compare squared: |d × (p − a)| ≤ tol·|d|  ⇔  (d × (p − a))² ≤ tol²·|d|².
bool shared_edge(const Vec2& u, const Vec2& v, const EdgeTable& other, double tol2) {
  const Vec2 e = v - u;
  if (e.squaredNorm() <= tol2) return true;
  // Branch-free over the edges: which edges pass is unpredictable, and there are few.
  const std::size_t m = other.p.size();
  bool shared = false;
  for (std::size_t c = 0; c < m; ++c) {
    const Vec2& d = other.d[c];
    const Vec2& a = other.p[c];
    const double su = cross(d, u - a), sv = cross(d, v - a);
    shared |= (e.dot(d) > 0.0) & (su * su <= other.limit[c]) & (sv * sv <= other.limit[c]);
  }
  return shared;
}

// n perpendicular to the contact line (p2 - p1 != 0), oriented from i toward j.
Vec2 line_normal(const Vec2& p1, const Vec2& p2, const Vec2& dc) {
  const Vec2 t = p2 - p1;
  Vec2 n = perp(t) / std::sqrt(t.squaredNorm());  // lengths ≥ eps_L ~ 1e-11 m: no under/overflow
  const double s = n.dot(dc);
  if (s < 0.0 || (s == 0.0 && (n.x() < 0.0 || (n.x() == 0.0 && n.y() < 0.0)))) n = -n;
  return n;
}

// n along the line of centres; +x when the centres coincide.
Vec2 centre_normal(const Vec2& dc) {
  const double len = std::hypot(dc.x(), dc.y());
  if (len > 0.0 && std::isfinite(len)) return dc / len;
  return Vec2(1.0, 0.0);
}

ContactGeometry overlap_impl(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                             double g, std::size_t first_clip_edge, OverlapPolygon* overlap) {
  const std::size_t n = pi.size(), m = pj.size();
  if (n > kMaxContactPolygonVertices || m > kMaxContactPolygonVertices) {
    throw InputError("convex_overlap: polygon with " + std::to_string(n > m ? n : m) + " vertices (at most " +
                     std::to_string(kMaxContactPolygonVertices) + ")");
  }
  if (!(g > 0.0) || !std::isfinite(g)) throw InputError("convex_overlap: length scale must be positive and finite");
  ContactGeometry r;
  if (overlap) overlap->size = 0;
  if (n < 3 || m < 3) return r;
  const double eps_area = kOverlapAreaTolerance * g * g;
  const double eps_len = kCrossingMergeTolerance * g;

  // Local frame at P_i's first vertex: the differences of nearby coordinates are exact, so the
  // result does not depend on the distance from the origin.
  const Vec2 o = pi[0];
  std::array<Vec2, kMaxContactPolygonVertices> li, lj;
  for (std::size_t k = 0; k < n; ++k) li[k] = pi[k] - o;
  for (std::size_t k = 0; k < m; ++k) lj[k] = pj[k] - o;
  const std::span<const Vec2> si(li.data(), n), sj(lj.data(), m);

  LabelledPolygon buf_a, buf_b;
  LabelledPolygon* cur = &buf_a;
  LabelledPolygon* next = &buf_b;
  for (std::size_t k = 0; k < n; ++k) cur->push(li[k], static_cast<int>(k));
  // Clip by P_j's edges starting at `first_clip_edge` (the edge facing P_i cuts P_i down to a sliver
  // first, so the later steps handle few vertices); the intersection does not depend on the order.
  const std::size_t first = first_clip_edge < m ? first_clip_edge : 0;
  for (std::size_t step = 0; step < m && cur->size > 0; ++step) {
    const std::size_t b = first + step < m ? first + step : first + step - m;
    const Vec2& a0 = lj[b];
    const Vec2& a1 = lj[b + 1 == m ? 0 : b + 1];
    if (a0 == a1) continue;  // a repeated vertex bounds nothing
    if (clip_step(*cur, a0, a1, static_cast<int>(n + b), *next)) std::swap(cur, next);
  }
  const LabelledPolygon& P = *cur;
  const std::size_t K = P.size;
  if (K < 3) return r;
  const std::span<const Vec2> pv(P.v.data(), K);
  if (overlap) {
    overlap->size = K;
    for (std::size_t k = 0; k < K; ++k) overlap->vertex[k] = P.v[k] + o;
  }
  const double area = signed_area(pv);
  if (!(area > eps_area)) return r;
  r.area = area;
  const Vec2 dc = cj - ci;

  // Crossings: vertices where the edge label switches between P_i and P_j, moved to the midpoint of
  // any run of shared edges around them.
  const auto nn = static_cast<int>(n);
  auto owner_j = [&](std::size_t e) { return P.label[e] >= nn; };
  // Shared status of each edge, evaluated on demand: -1 unknown, 0 no, 1 yes.
  std::array<signed char, kMaxOverlapVertices> shared_state;
  shared_state.fill(-1);
  const double tol2 = eps_len * eps_len;
  const EdgeTable edges_i(si, tol2), edges_j(sj, tol2);
  auto shared = [&](std::size_t e) {
    if (shared_state[e] < 0) {
      const Vec2& u = P.v[e];
      const Vec2& v = P.v[e + 1 == K ? 0 : e + 1];
      shared_state[e] = shared_edge(u, v, owner_j(e) ? edges_i : edges_j, tol2) ? 1 : 0;
    }
    return shared_state[e] == 1;
  };
  std::array<Vec2, kMaxOverlapVertices> cross_pt;
  std::size_t count = 0;
  bool all_shared = false;
  for (std::size_t k = 0; k < K && !all_shared; ++k) {
    const std::size_t prev = k == 0 ? K - 1 : k - 1;
    if (owner_j(prev) == owner_j(k)) continue;
    std::size_t back = 0, fwd = 0;  // shared edges before and after vertex k
    while (back < K && shared((k + K - 1 - back) % K)) ++back;
    while (back + fwd < K && shared((k + fwd) % K)) ++fwd;
    if (back + fwd >= K) {
      all_shared = true;  // both boundaries coincide all around: identical polygons
      break;
    }
    cross_pt[count++] = 0.5 * (P.v[(k + K - back) % K] + P.v[(k + fwd) % K]);
  }
  if (all_shared) count = 0;
  r.crossings = static_cast<int>(count);

  // Cancel pairs of neighbouring crossings closer than eps_L (cyclically), until none is left.
  bool cancelled = true;
  while (cancelled && count >= 2) {
    cancelled = false;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t k1 = k + 1 == count ? 0 : k + 1;
      if ((cross_pt[k] - cross_pt[k1]).squaredNorm() > eps_len * eps_len) continue;
      // Remove entries k and k1 (k1 == 0 when k is the last one).
      std::size_t w = 0;
      for (std::size_t s = 0; s < count; ++s) {
        if (s != k && s != k1) cross_pt[w++] = cross_pt[s];
      }
      count = w;
      cancelled = true;
      break;
    }
  }
  r.distinct_crossings = static_cast<int>(count);

  if (count < 2) {
    r.kind = ContactGeometry::Kind::enclosed;
    r.point = centroid(pv) + o;
    r.p1 = r.p2 = r.point;
    r.normal = centre_normal(dc);
    return r;
  }
  // The pair farthest apart (the only pair in the normal case); first found wins ties.
  std::size_t best_a = 0, best_b = 1;
  double best = -1.0;
  for (std::size_t a = 0; a + 1 < count; ++a) {
    for (std::size_t b = a + 1; b < count; ++b) {
      const double d2 = (cross_pt[a] - cross_pt[b]).squaredNorm();
      if (d2 > best) {
        best = d2;
        best_a = a;
        best_b = b;
      }
    }
  }
  r.kind = ContactGeometry::Kind::line;
  r.p1 = cross_pt[best_a] + o;
  r.p2 = cross_pt[best_b] + o;
  r.point = 0.5 * (cross_pt[best_a] + cross_pt[best_b]) + o;
  r.normal = line_normal(cross_pt[best_a], cross_pt[best_b], dc);
  return r;
}

}  // namespace

ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci,
                               const Vec2& cj, double length_scale, std::size_t first_clip_edge) {
  return overlap_impl(pi, pj, ci, cj, length_scale, first_clip_edge, nullptr);
}

ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci,
                               const Vec2& cj, double length_scale, OverlapPolygon& overlap) {
  return overlap_impl(pi, pj, ci, cj, length_scale, 0, &overlap);
}

std::size_t facing_edge(std::span<const Vec2> p, const Vec2& d) {
  // The facing edge is one of the two edges at p's support vertex in direction d.
  const std::size_t n = p.size();
  std::size_t s = 0;
  double best = p[0].dot(d);
  for (std::size_t a = 1; a < n; ++a) {
    const double h = p[a].dot(d);
    if (h > best) {
      best = h;
      s = a;
    }
  }
  const std::size_t prev = s == 0 ? n - 1 : s - 1;
  const Vec2 e_out = p[s + 1 == n ? 0 : s + 1] - p[s];  // edge s -> s+1
  const Vec2 e_in = p[s] - p[prev];                      // edge s-1 -> s
  const double l_out = e_out.norm(), l_in = e_in.norm();
  // Outward normal of edge e (counter-clockwise polygon): (e_y, −e_x)/|e|.
  const double f_out = l_out > 0 ? (e_out.y() * d.x() - e_out.x() * d.y()) / l_out : -1e300;
  const double f_in = l_in > 0 ? (e_in.y() * d.x() - e_in.x() * d.y()) / l_in : -1e300;
  return f_out >= f_in ? s : prev;
}

bool edge_separates(std::span<const Vec2> p, std::size_t edge, std::span<const Vec2> q, double slack) {
  const std::size_t n = p.size();
  if (edge >= n) return false;
  const Vec2& a = p[edge];
  const Vec2 e = p[edge + 1 == n ? 0 : edge + 1] - a;
  const double e2 = e.squaredNorm();
  if (!(e2 > 0)) return false;
  // A vertex v penetrates by more than slack when (e × (v − a))/|e| < −slack: compared squared, no sqrt.
  const double limit2 = slack * slack * e2;
  for (const Vec2& v : q) {
    const double s = e.y() * (v.x() - a.x()) - e.x() * (v.y() - a.y());
    if (s < 0 && s * s > limit2) return false;
  }
  return true;
}

}  // namespace frac::geometry
