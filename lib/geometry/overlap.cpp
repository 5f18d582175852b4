#include "geometry/overlap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.hpp"
#include "geometry/overlap_lines.hpp"
#include "geometry/polygon.hpp"

namespace frac::geometry {
namespace {
using detail::kMaxRegularVertices;
using detail::line_normal;
using detail::OverlapFrame;
using detail::regular_vertices;

// The clipper's working polygon: vertex k and the label of its edge k -> k+1, which names the
// original edge the edge lies on: 0..n-1 an edge of P_i, n + b edge b of P_j. Room for twice the
// largest overlap polygon (a clip step at most doubles the count; the size is checked after each step)
// and for a copy of the first vertex after the last.
constexpr std::size_t kClipCapacity = 2 * kMaxOverlapVertices + 1;
struct LabelledPolygon {
  std::array<Vec2, kClipCapacity> v;
  std::array<int, kClipCapacity> label;
  std::size_t size = 0;
};

// One Sutherland-Hodgman step: keep the part of `in` on the left of the directed line a -> b
// (closed half-plane, no tolerance). The new edge along the line gets `line_label`; pieces of old
// edges keep theirs. An inside vertex exactly on the line is not repeated as a crossing.
// Returns false, leaving `out` untouched, when every vertex of `in` is on the left or on the line:
// the step would copy `in` unchanged. (Sets the copy of the first vertex after the last in `in`.)
bool clip_step(LabelledPolygon& in, const Vec2& a, const Vec2& b, int line_label, LabelledPolygon& out) {
  const Vec2 d = b - a;
  const std::size_t n = in.size;
  std::array<double, kClipCapacity> side;  // cross(d, p - a): > 0 on the left
  bool all_inside = true;
  for (std::size_t k = 0; k < n; ++k) {
    side[k] = cross(d, in.v[k] - a);
    all_inside &= side[k] >= 0.0;  // NaN counts as outside
  }
  if (all_inside) return false;
  side[n] = side[0];
  in.v[n] = in.v[0];
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double sp = side[k], sq = side[k + 1];
    const Vec2& p = in.v[k];
    if (sp >= 0.0) {
      out.v[m] = p;
      out.label[m++] = in.label[k];
      if (sq < 0.0) {
        // Leaving: from here the boundary of the result runs along the clip line.
        if (sp > 0.0) {
          out.v[m] = p + (sp / (sp - sq)) * (in.v[k + 1] - p);
          out.label[m++] = line_label;
        } else {
          out.label[m - 1] = line_label;
        }
      }
    } else if (sq > 0.0) {
      // Entering: the rest of edge pq is a piece of the old edge. (sq == 0: q itself comes next.)
      out.v[m] = p + (sp / (sp - sq)) * (in.v[k + 1] - p);
      out.label[m++] = in.label[k];
    }
  }
  // Cannot happen for convex input within the vertex limit: each clip adds at most one vertex
  // except where round-off makes vertices alternate in and out along the clip line.
  if (m > kMaxOverlapVertices) throw RuntimeError("convex_overlap: overlap polygon exceeds its capacity");
  out.size = m;
  return true;
}

// The edges of a polygon as the shared-edge test needs them: d_c = p_{c+1} − p_c and tol²·|d_c|².
// Filled on first use: with a hint, most pairs need none.
struct EdgeTable {
  std::array<double, kMaxContactPolygonVertices> dx, dy, limit;
  std::span<const Vec2> p;
  bool filled = false;
  void fill(std::span<const Vec2> polygon, double tol2) {
    p = polygon;
    const std::size_t m = p.size();
    for (std::size_t c = 0; c < m; ++c) {
      const Vec2 d = p[c + 1 == m ? 0 : c + 1] - p[c];
      dx[c] = d.x();
      dy[c] = d.y();
      limit[c] = tol2 * d.squaredNorm();
    }
    filled = true;
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
    const Vec2 d(other.dx[c], other.dy[c]);
    const Vec2& a = other.p[c];
    const double su = cross(d, u - a), sv = cross(d, v - a);
    shared |= (e.dot(d) > 0.0) & (su * su <= other.limit[c]) & (sv * sv <= other.limit[c]);
  }
  return shared;
}

// The three edges c−1, c, c+1 of a polygon (`p` in the local frame) as the shared-edge test needs them.
// When the overlap lies within the reach of edge c (edge_reach), no other edge line comes within tol of
// it, and the test over these three is the test over all.
struct NearEdges {
  std::array<Vec2, 3> a, d;
  std::array<double, 3> limit;
  bool filled = false;
  void fill(std::span<const Vec2> p, std::size_t c, double tol2) {
    const std::size_t m = p.size();
    const std::size_t lines[3] = {c == 0 ? m - 1 : c - 1, c, c + 1 == m ? 0 : c + 1};
    for (std::size_t s = 0; s < 3; ++s) {
      const std::size_t l = lines[s];
      a[s] = p[l];
      d[s] = p[l + 1 == m ? 0 : l + 1] - a[s];
      limit[s] = tol2 * d[s].squaredNorm();
    }
    filled = true;
  }
};

bool shared_edge(const Vec2& u, const Vec2& v, const NearEdges& other, double tol2) {
  const Vec2 e = v - u;
  if (e.squaredNorm() <= tol2) return true;
  bool shared = false;
  for (std::size_t s = 0; s < 3; ++s) {
    const Vec2& d = other.d[s];
    const double su = cross(d, u - other.a[s]), sv = cross(d, v - other.a[s]);
    shared |= (e.dot(d) > 0.0) & (su * su <= other.limit[s]) & (sv * sv <= other.limit[s]);
  }
  return shared;
}

// Whether every vertex lies within `reach` of the midpoint of edge c of `p`.
bool within_reach(const Vec2* v, std::size_t count, std::span<const Vec2> p, std::size_t c, double reach) {
  const Vec2 mid = 0.5 * (p[c] + p[c + 1 == p.size() ? 0 : c + 1]);
  const double r2 = reach * reach;
  bool inside = true;
  for (std::size_t k = 0; k < count; ++k) inside &= (v[k] - mid).squaredNorm() <= r2;
  return inside;
}

// n along the line of centres; +x when the centres coincide.
Vec2 centre_normal(const Vec2& dc) {
  const double len = std::hypot(dc.x(), dc.y());
  if (len > 0.0 && std::isfinite(len)) return dc / len;
  return Vec2(1.0, 0.0);
}

// The overlap by clipping (convex_overlap's method), then from its lines when it is regular (the lines go to
// `cache`). Kept out of line: its buffers make a large stack frame that the cached path does not need.
[[gnu::noinline]] ContactGeometry clipped_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj,
                                                  std::size_t first_clip_edge, const OverlapHint* hint, OverlapFrame& f,
                                                  OverlapLines* cache);

ContactGeometry overlap_impl(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                             double g, std::size_t first_clip_edge, const OverlapHint* hint, OverlapPolygon* overlap) {
  const std::size_t n = pi.size(), m = pj.size();
  if (n > kMaxContactPolygonVertices || m > kMaxContactPolygonVertices) {
    throw InputError("convex_overlap: polygon with " + std::to_string(n > m ? n : m) + " vertices (at most " +
                     std::to_string(kMaxContactPolygonVertices) + ")");
  }
  if (!(g > 0.0) || !std::isfinite(g)) throw InputError("convex_overlap: length scale must be positive and finite");
  if (overlap) overlap->size = 0;
  OverlapLines* const cache = hint ? hint->lines : nullptr;
  const std::size_t cached = cache ? cache->size : 0;
  if (cache) cache->size = 0;  // until a regular overlap is found
  if (n < 3 || m < 3) return {};
  const double eps_len = crossing_merge_tolerance(g, pi[0], pj[0]);
  const double tol = 4 * eps_len;  // the margins of a regular overlap
  const Vec2 o = pi[0];
  OverlapFrame f({pi, pj, o.x(), o.y(), static_cast<int>(n), static_cast<int>(m), tol, tol * tol, {}}, o, cj - ci,
                 kOverlapAreaTolerance * g * g, eps_len, overlap);
  if (hint) {
    f.edges.set_near(false, hint->edge_i, hint->reach_i);
    f.edges.set_near(true, hint->edge_j, hint->reach_j);
  }
  // The lines of the pair's last overlap, if they still make a regular polygon: it is the overlap, no
  // clipping needed.
  if (cached >= 3 && cached <= kMaxRegularVertices) {
    bool known = true;
    for (std::size_t k = 0; k < cached; ++k) {
      f.label[k] = cache->label[k];
      known &= f.label[k] < static_cast<int>(n + m);
    }
    if (known && regular_vertices(f.edges, f.label.data(), cached, f.v.data())) {
      cache->size = static_cast<std::uint8_t>(cached);
      return f.regular_result(cached);
    }
  }
  return clipped_overlap(pi, pj, first_clip_edge, hint, f, cache);
}

// The pieces of clipped_overlap, forced inline: they share its stack frame and registers as when they were
// written in one body (the contact force's hot path).

// P_i in the local frame about o, as the clipper's first polygon (edge k labelled k), and P_j beside it.
[[gnu::always_inline]] inline void to_local_frame(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& o,
                                                  std::array<Vec2, kMaxContactPolygonVertices>& li,
                                                  std::array<Vec2, kMaxContactPolygonVertices>& lj,
                                                  LabelledPolygon& start) {
  const std::size_t n = pi.size(), m = pj.size();
  for (std::size_t k = 0; k < n; ++k) {
    li[k] = pi[k] - o;
    start.v[k] = li[k];
    start.label[k] = static_cast<int>(k);
  }
  start.size = n;
  for (std::size_t k = 0; k < m; ++k) lj[k] = pj[k] - o;
}

// P_i ∩ P_j: `cur` (P_i) clipped by the half-planes of P_j's edges (sj), starting at edge `first`. The edge
// facing P_i cuts P_i down to a sliver first, so the later steps handle few vertices; the intersection does
// not depend on the order. Returns whether the hint's reach of P_j's facing edge holds what is left.
[[gnu::always_inline]] inline bool clip_by_pj(LabelledPolygon*& cur, LabelledPolygon*& next, std::span<const Vec2> sj,
                                              std::size_t n, std::size_t first, bool hinted_j,
                                              const OverlapHint* hint) {
  const std::size_t m = sj.size();
  auto clip_by = [&](std::size_t step) {
    const std::size_t b = first + step < m ? first + step : first + step - m;
    const Vec2& a0 = sj[b];
    const Vec2& a1 = sj[b + 1 == m ? 0 : b + 1];
    if (a0 == a1) return;  // a repeated vertex bounds nothing
    if (clip_step(*cur, a0, a1, static_cast<int>(n + b), *next)) std::swap(cur, next);
  };
  clip_by(0);
  // With a hint: when what is left of P_i lies within the reach of P_j's facing edge, no edge line of
  // P_j but the two next to it can cut it (nor come within tol of the overlap): the steps of the
  // others would keep everything, and are left out.
  const bool near_j = hinted_j && cur->size > 0 && within_reach(cur->v.data(), cur->size, sj, first, hint->reach_j);
  if (near_j) {
    clip_by(1);
    if (cur->size > 0) clip_by(m - 1);
  } else {
    for (std::size_t step = 1; step < m && cur->size > 0; ++step) clip_by(step);
  }
  return near_j;
}

// Whether the clipped polygon P (at least 3 vertices) is a regular overlap: then its lines in order from the
// lowest label are in f.label, its vertices from them in f.v, and the lines in `cache`. An edge shorter than
// tol/2 here is shorter than tol from the lines as well (the vertices differ by round-off): not regular, no
// need to try (the thin slivers of neighbours barely turned against each other).
[[gnu::always_inline]] inline bool regular_overlap(const LabelledPolygon& P, OverlapFrame& f, OverlapLines* cache) {
  const std::size_t K = P.size;
  bool short_edge = false;
  for (std::size_t k = 0; k < K; ++k)
    short_edge |= (P.v[k + 1 == K ? 0 : k + 1] - P.v[k]).squaredNorm() <= 0.25 * f.edges.tol2;
  if (K <= kMaxRegularVertices && !short_edge) {
    std::size_t start = 0;
    for (std::size_t k = 1; k < K; ++k) start = P.label[k] < P.label[start] ? k : start;
    for (std::size_t k = 0; k < K; ++k) f.label[k] = P.label[start + k < K ? start + k : start + k - K];
    if (regular_vertices(f.edges, f.label.data(), K, f.v.data())) {
      if (cache) {
        cache->size = static_cast<std::uint8_t>(K);
        for (std::size_t k = 0; k < K; ++k) cache->label[k] = static_cast<std::uint8_t>(f.label[k]);
      }
      return true;
    }
  }
  return false;
}

// The crossings of the boundaries of P_i and P_j (in si, sj) on the overlap P: vertices where the edge
// label switches between P_i and P_j, moved to the midpoint of any run of shared edges around them (an
// edge on both boundaries belongs to neither). None when the boundaries coincide all around (identical
// polygons). Returns their count.
[[gnu::always_inline]] inline std::size_t boundary_crossings(const LabelledPolygon& P, std::span<const Vec2> si,
                                                             std::span<const Vec2> sj, const OverlapHint* hint,
                                                             bool near_j, std::size_t first, double eps_len,
                                                             std::array<Vec2, kMaxOverlapVertices>& cross_pt) {
  const std::size_t n = si.size(), K = P.size;
  const auto nn = static_cast<int>(n);
  auto owner_j = [&](std::size_t e) { return P.label[e] >= nn; };
  // Shared status of each edge, evaluated on demand: -1 unknown, 0 no, 1 yes.
  std::array<signed char, kMaxOverlapVertices> shared_state;
  shared_state.fill(-1);
  const double tol2 = eps_len * eps_len;
  EdgeTable edges_i, edges_j;
  NearEdges near_edges_i, near_edges_j;
  const bool near_i =
      hint && hint->edge_i < n && hint->reach_i > 0.0 && within_reach(P.v.data(), K, si, hint->edge_i, hint->reach_i);
  auto shared = [&](std::size_t e) {
    if (shared_state[e] < 0) {
      const Vec2& u = P.v[e];
      const Vec2& v = P.v[e + 1 == K ? 0 : e + 1];
      if (owner_j(e) ? near_i : near_j) {
        NearEdges& other = owner_j(e) ? near_edges_i : near_edges_j;
        if (!other.filled) other.fill(owner_j(e) ? si : sj, owner_j(e) ? hint->edge_i : first, tol2);
        shared_state[e] = shared_edge(u, v, other, tol2) ? 1 : 0;
      } else {
        EdgeTable& other = owner_j(e) ? edges_i : edges_j;
        if (!other.filled) other.fill(owner_j(e) ? si : sj, tol2);
        shared_state[e] = shared_edge(u, v, other, tol2) ? 1 : 0;
      }
    }
    return shared_state[e] == 1;
  };
  // An index below 2K wrapped into [0, K): one subtraction instead of a division.
  auto wrap = [K](std::size_t k) { return k >= K ? k - K : k; };
  std::size_t count = 0;
  bool all_shared = false;
  for (std::size_t k = 0; k < K && !all_shared; ++k) {
    const std::size_t prev = k == 0 ? K - 1 : k - 1;
    if (owner_j(prev) == owner_j(k)) continue;
    std::size_t back = 0, fwd = 0;  // shared edges before and after vertex k
    while (back < K && shared(wrap(k + K - 1 - back))) ++back;
    while (back + fwd < K && shared(wrap(k + fwd))) ++fwd;
    if (back + fwd >= K) {
      all_shared = true;  // both boundaries coincide all around: identical polygons
      break;
    }
    cross_pt[count++] = 0.5 * (P.v[wrap(k + K - back)] + P.v[wrap(k + fwd)]);
  }
  if (all_shared) count = 0;
  return count;
}

// Cancel pairs of neighbouring crossings closer than eps_L (cyclically), until none is left: an excursion
// of one boundary that does not cross the other. Returns the count left.
[[gnu::always_inline]] inline std::size_t cancel_close_crossings(std::array<Vec2, kMaxOverlapVertices>& cross_pt,
                                                                 std::size_t count, double eps_len) {
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
  return count;
}

// The contact line through the two crossings farthest apart (the only pair in the normal case; first found
// wins ties), or, with fewer than 2, the enclosed case at the overlap's centroid along the line of centres.
[[gnu::always_inline]] inline void contact_from_crossings(ContactGeometry& r,
                                                          const std::array<Vec2, kMaxOverlapVertices>& cross_pt,
                                                          std::size_t count, std::span<const Vec2> pv, const Vec2& o,
                                                          const Vec2& dc) {
  if (count < 2) {
    r.kind = ContactGeometry::Kind::enclosed;
    r.point = centroid(pv) + o;
    r.p1 = r.p2 = r.point;
    r.normal = centre_normal(dc);
    return;
  }
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
}

ContactGeometry clipped_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, std::size_t first_clip_edge,
                                const OverlapHint* hint, OverlapFrame& f, OverlapLines* cache) {
  const std::size_t n = pi.size(), m = pj.size();
  const Vec2& o = f.o;
  const double eps_area = f.eps_area, eps_len = f.eps_len;
  OverlapPolygon* const overlap = f.overlap;
  ContactGeometry r;
  std::array<Vec2, kMaxContactPolygonVertices> li, lj;
  LabelledPolygon buf_a, buf_b;
  LabelledPolygon* cur = &buf_a;
  LabelledPolygon* next = &buf_b;
  to_local_frame(pi, pj, o, li, lj, *cur);
  const std::span<const Vec2> si(li.data(), n), sj(lj.data(), m);
  const bool hinted_j = hint && hint->edge_j < m && hint->reach_j > 0.0;
  const std::size_t first = hinted_j ? hint->edge_j : first_clip_edge < m ? first_clip_edge : 0;
  const bool near_j = clip_by_pj(cur, next, sj, n, first, hinted_j, hint);
  const LabelledPolygon& P = *cur;
  const std::size_t K = P.size;
  if (K < 3) return r;
  if (regular_overlap(P, f, cache)) return f.regular_result(K);
  const std::span<const Vec2> pv(P.v.data(), K);
  if (overlap) {
    overlap->size = K;
    for (std::size_t k = 0; k < K; ++k) overlap->vertex[k] = P.v[k] + o;
  }
  const double area = signed_area(pv);
  if (!(area > eps_area)) return r;
  r.area = area;
  std::array<Vec2, kMaxOverlapVertices> cross_pt;
  std::size_t count = boundary_crossings(P, si, sj, hint, near_j, first, eps_len, cross_pt);
  r.crossings = static_cast<int>(count);
  count = cancel_close_crossings(cross_pt, count, eps_len);
  r.distinct_crossings = static_cast<int>(count);
  contact_from_crossings(r, cross_pt, count, pv, o, f.dc);
  return r;
}

}  // namespace

ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, std::size_t first_clip_edge) {
  return overlap_impl(pi, pj, ci, cj, length_scale, first_clip_edge, nullptr, nullptr);
}

ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, const OverlapHint& hint) {
  return overlap_impl(pi, pj, ci, cj, length_scale, hint.edge_j, &hint, nullptr);
}

double edge_reach(std::span<const Vec2> p, std::size_t edge) {
  const std::size_t m = p.size();
  if (edge >= m) return 0.0;
  const Vec2 mid = 0.5 * (p[edge] + p[edge + 1 == m ? 0 : edge + 1]);
  double reach = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < m; ++c) {
    const std::size_t gap = c > edge ? c - edge : edge - c;
    if (gap <= 1 || gap == m - 1) continue;  // the edge itself and its two neighbours
    const Vec2 d = p[c + 1 == m ? 0 : c + 1] - p[c];
    const double len = std::sqrt(d.squaredNorm());
    if (!(len > 0.0)) continue;  // a repeated vertex bounds nothing
    reach = std::min(reach, cross(d, mid - p[c]) / len);
  }
  // A margin far above round-off: a point within the reach is at least 1e-3 of the distance inside.
  return reach > 0.0 ? (1.0 - 1e-3) * reach : 0.0;
}

ContactGeometry convex_overlap(std::span<const Vec2> pi, std::span<const Vec2> pj, const Vec2& ci, const Vec2& cj,
                               double length_scale, OverlapPolygon& overlap) {
  return overlap_impl(pi, pj, ci, cj, length_scale, 0, nullptr, &overlap);
}

}  // namespace frac::geometry
