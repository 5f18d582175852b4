#include "dem/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/overlap.hpp"

namespace frac::dem {
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

ContactSearch::ContactSearch(const mesh::CellMesh& mesh, const Bodies& bodies)
    : mesh_(&mesh),
      bodies_(&bodies),
      world_(mesh.vertex.size()),
      cell_of_(bodies.n),
      sorted_(bodies.n),
      grid_body_(bodies.n),
      skin_(0.2 * bodies.length_scale) {
  inv_diameter_.resize(bodies.n);
  for (std::size_t k = 0; k < bodies.n; ++k) inv_diameter_[k] = 1.0 / bodies.diameter[k];
  // The reach of every edge of every cell (body frame: a rigid motion does not change it).
  edge_reach_.resize(mesh.vertex.size());
  for (std::size_t k = 0; k < bodies.n; ++k) {
    const auto poly = mesh.polygon(k);
    const auto offset = static_cast<std::size_t>(mesh.vertex_offset[k]);
    for (std::size_t e = 0; e < poly.size(); ++e) edge_reach_[offset + e] = geometry::edge_reach(poly, e);
  }
}

// Vertices of this thread's cells in world coordinates, and how far its cells' centroids have moved since the
// neighbour list was built: the two largest distances, into this thread's moved_ slot (NaN counts as
// infinitely far). A polygon never leaves its bounding circle about its centroid, whatever it turns, so a pair
// left out of the list (circles more than the skin apart) cannot overlap while the two largest distances sum
// to at most the skin.
void ContactSearch::world_vertices_and_staleness(std::span<const double> q) {
  const std::size_t n = bodies_->n;
  const double* x = q.data();
  const double* y = x + n;
  const double* phi = y + n;
  const bool built = ref_.size() == q.size();
  const double* ref = ref_.data();
  Moved moved{built ? 0.0 : kInfinity, built ? 0.0 : kInfinity};
  const Range mine = this_thread_range(n);
  // (Raw pointers and the centroid in locals: a store to world may alias x and y, which would be reloaded.)
  const auto* offset = mesh_->vertex_offset.data();
  const Vec2* body = mesh_->vertex.data();
  Vec2* world = world_.data();
  for (std::size_t k = mine.first; k < mine.last; ++k) {
    const double c = std::cos(phi[k]), s = std::sin(phi[k]);
    const double xk = x[k], yk = y[k];
    const auto e = static_cast<std::size_t>(offset[k + 1]);
    for (auto v = static_cast<std::size_t>(offset[k]); v < e; ++v) {
      const double px = body[v].x(), py = body[v].y();
      world[v] = Vec2(xk + c * px - s * py, yk + s * px + c * py);
    }
    if (built) {
      const double dx = x[k] - ref[k], dy = y[k] - ref[n + k];
      const double d2 = dx * dx + dy * dy;
      if (!(d2 <= moved.second * moved.second)) moved.add(std::isnan(d2) ? kInfinity : std::sqrt(d2));  // (rarely)
    }
  }
  moved_.mine() = moved;
}

void ContactSearch::rebuild(std::span<const double> q, ContactList& out) {
  const std::size_t n = bodies_->n;
  const double* x = q.data();
  const double* y = x + n;
  if (thread_index() == 0) {  // (one thread; the others wait at the barrier after)
    ++rebuilds_;
    ref_.assign(q.begin(), q.end());
    // The old list, indexed by its first cell, so that a pair found again keeps what it has learnt (its
    // separating edges, whether it overlapped, the lines of its overlap): less work. (The kept facing edge
    // sets the clip order, which only an irregular overlap's result depends on, at round-off.)
    std::swap(previous_, neighbours_);
    neighbours_.clear();
    previous_first_.assign(n + 1, 0);
    for (const auto& pair : previous_) ++previous_first_[static_cast<std::size_t>(pair.i) + 1];
    for (std::size_t i = 0; i < n; ++i) previous_first_[i + 1] += previous_first_[i];
    // Cell list: grid cells of side 2·max bounding radius, so every overlapping pair sits in the same or
    // adjacent grid cells. Counting sort into the grid (deterministic order: by grid cell, then index).
    double xmin = x[0], xmax = x[0], ymin = y[0], ymax = y[0];
    for (std::size_t k = 1; k < n; ++k) {
      xmin = std::min(xmin, x[k]);
      xmax = std::max(xmax, x[k]);
      ymin = std::min(ymin, y[k]);
      ymax = std::max(ymax, y[k]);
    }
    grid_x_ = grid_y_ = 0;
    // A non-finite position ends the run at the step's check; build no list from it.
    if (std::isfinite(xmax - xmin) && std::isfinite(ymax - ymin)) {
      const double side = 2 * bodies_->max_bound_radius + skin_;
      // Bound the grid size (fragments flying far apart): at most ~4 grid cells per body.
      const double span_x = xmax - xmin, span_y = ymax - ymin;
      double cell = side;
      while ((span_x / cell + 1) * (span_y / cell + 1) > 4.0 * static_cast<double>(n) + 16) cell *= 2;
      const auto gx = static_cast<std::size_t>(span_x / cell) + 1;
      const auto gy = static_cast<std::size_t>(span_y / cell) + 1;
      cell_start_.assign(gx * gy + 1, 0);
      for (std::size_t k = 0; k < n; ++k) {
        const auto cx = std::min(gx - 1, static_cast<std::size_t>((x[k] - xmin) / cell));
        const auto cy = std::min(gy - 1, static_cast<std::size_t>((y[k] - ymin) / cell));
        cell_of_[k] = static_cast<std::int32_t>(cy * gx + cx);
        ++cell_start_[static_cast<std::size_t>(cell_of_[k]) + 1];
      }
      for (std::size_t c = 0; c < gx * gy; ++c) cell_start_[c + 1] += cell_start_[c];
      // Fill using a running cursor per grid cell (reuse the start array shifted by one).
      std::vector<std::int32_t>& start = cell_start_;
      for (std::size_t k = 0; k < n; ++k) {
        const auto c = static_cast<std::size_t>(cell_of_[k]);
        sorted_[static_cast<std::size_t>(start[c]++)] = static_cast<std::int32_t>(k);
      }
      for (std::size_t c = gx * gy; c > 0; --c) start[c] = start[c - 1];
      start[0] = 0;
      // The bodies' centres and radii in grid order: the scan below reads them one grid cell after another.
      const double* r = bodies_->bound_radius.data();
      for (std::size_t s = 0; s < n; ++s) {
        const auto k = static_cast<std::size_t>(sorted_[s]);
        grid_body_[s] = {x[k], y[k], r[k], sorted_[s]};
      }
      grid_x_ = gx;
      grid_y_ = gy;
    }
  }
  team_barrier();
  // The pairs (i, j > i) in order of i, then of the grid scan: threads take contiguous ranges of i (in thread
  // order) into their own buffers, joined in thread order: the same list whatever the thread count.
  const auto t = static_cast<std::size_t>(thread_index()), nt = static_cast<std::size_t>(thread_count());
  auto& buf = thread_pairs_[t];
  buf.clear();
  const std::size_t gx = grid_x_, gy = grid_y_;
  const GridBody* body = grid_body_.data();
  auto pairs_of = [&](std::size_t i) {
    const auto ci = static_cast<std::size_t>(cell_of_[i]);
    const double xi = x[i], yi = y[i], ri = bodies_->bound_radius[i];
    const std::size_t cx = ci % gx, cy = ci / gx;
    for (std::size_t ny = (cy > 0 ? cy - 1 : 0); ny <= std::min(gy - 1, cy + 1); ++ny) {
      for (std::size_t nxc = (cx > 0 ? cx - 1 : 0); nxc <= std::min(gx - 1, cx + 1); ++nxc) {
        const std::size_t c = ny * gx + nxc;
        // A grid cell's bodies are in order of index: skip to the first j > i (one loop exit to predict per
        // grid cell, rather than a coin toss per body).
        auto s = static_cast<std::size_t>(cell_start_[c]);
        const auto end = static_cast<std::size_t>(cell_start_[c + 1]);
        while (s < end && static_cast<std::size_t>(body[s].index) <= i) ++s;
        for (; s < end; ++s) {
          const auto j = static_cast<std::size_t>(body[s].index);
          const double dx = body[s].x - xi, dy = body[s].y - yi;
          const double reach = ri + body[s].r + skin_;
          if (dx * dx + dy * dy >= reach * reach) continue;
          const auto* const begin = previous_.data() + previous_first_[i];
          const auto* const last = previous_.data() + previous_first_[i + 1];
          const auto* const known =
              std::find_if(begin, last, [&](const NeighbourPair& o) { return o.j == static_cast<std::int32_t>(j); });
          if (known != last) {
            buf.push_back(*known);
            continue;
          }
          const Vec2 dij(dx, dy);
          buf.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j),
                         static_cast<std::int32_t>(geometry::facing_edge(world_polygon(i), dij)),
                         static_cast<std::int32_t>(geometry::facing_edge(world_polygon(j), -dij)), false, 0, 0,
                         {}});
        }
      }
    }
  };
  if (gx > 0) {
    for (std::size_t i = n * t / nt; i < n * (t + 1) / nt; ++i) pairs_of(i);
  }
  team_barrier();
  if (t == 0) {  // (one thread; the others wait at the barrier after)
    for (std::size_t b = 0; b < nt; ++b)
      neighbours_.insert(neighbours_.end(), thread_pairs_[b].begin(), thread_pairs_[b].end());
    const std::size_t pairs = neighbours_.size();
    if (geometry_.size() < pairs) {
      geometry_.resize(pairs + pairs / 4);
      pair_state_.resize(pairs + pairs / 4);
    }
    out.reserve(pairs + pairs / 4);  // (at most one contact per pair)
    pair_schedule_.reset(pairs, nt);
  }
  team_barrier();
}

// Pair p at state (x, y): bounding circles, then the separating edges, then the overlap geometry, its contact
// into `fill` (or, null, the pair's own slot). Cheap rejection first: a slack below eps_A / (r_i + r_j) skips no pair convex_overlap
// would keep, so the order of the tests changes no result, only the time: a pair that overlapped at the last
// search goes straight to clipping; the others try the facing edges that last separated them (cached per
// pair), then the current facing edges, which become the cached ones when they separate. Returns whether
// the bounding circles overlap. Inline, up to the cached edges (what most pairs need); the rest out of line.
inline bool ContactSearch::test_pair(std::size_t p, const double* x, const double* y, double slack, Fill* fill) {
  auto& pair = neighbours_[p];
  const auto i = static_cast<std::size_t>(pair.i), j = static_cast<std::size_t>(pair.j);
  const double dx = x[j] - x[i], dy = y[j] - y[i];
  const double reach = bodies_->bound_radius[i] + bodies_->bound_radius[j];
  if (!(dx * dx + dy * dy < reach * reach)) {
    pair.overlapping = false;
    pair_state_[p] = PairState::apart;
    return false;
  }
  pair_state_[p] = PairState::candidate;
  // (Each test starts from the vertex that lay deepest at the last one: mostly, three vertices tested.)
  if (!pair.overlapping &&
      (geometry::edge_separates(world_polygon(i), static_cast<std::size_t>(pair.edge_i), world_polygon(j), slack,
                                pair.deepest_i) ||
       geometry::edge_separates(world_polygon(j), static_cast<std::size_t>(pair.edge_j), world_polygon(i), slack,
                                pair.deepest_j)))
    return true;
  test_pair_further(p, x, y, slack, fill);
  return true;
}

// test_pair past the cached edges: the current facing edges, then the overlap.
void ContactSearch::test_pair_further(std::size_t p, const double* x, const double* y, double slack, Fill* fill) {
  auto& pair = neighbours_[p];
  const auto i = static_cast<std::size_t>(pair.i), j = static_cast<std::size_t>(pair.j);
  const auto pi = world_polygon(i), pj = world_polygon(j);
  if (!pair.overlapping) {
    const Vec2 dc(x[j] - x[i], y[j] - y[i]);
    const auto fi = geometry::facing_edge(pi, dc), fj = geometry::facing_edge(pj, -dc);
    // (A facing edge that is the cached one was just tested.)
    if ((fi != static_cast<std::size_t>(pair.edge_i) && geometry::edge_separates(pi, fi, pj, slack, pair.deepest_i)) ||
        (fj != static_cast<std::size_t>(pair.edge_j) && geometry::edge_separates(pj, fj, pi, slack, pair.deepest_j))) {
      pair.edge_i = static_cast<std::int32_t>(fi);
      pair.edge_j = static_cast<std::int32_t>(fj);
      return;
    }
  }
  geometry::OverlapHint hint;
  hint.edge_i = static_cast<std::size_t>(pair.edge_i);
  hint.edge_j = static_cast<std::size_t>(pair.edge_j);
  hint.reach_i = edge_reach_[static_cast<std::size_t>(mesh_->vertex_offset[i]) + hint.edge_i];
  hint.reach_j = edge_reach_[static_cast<std::size_t>(mesh_->vertex_offset[j]) + hint.edge_j];
  hint.lines = &pair.lines;
  const auto geo = geometry::convex_overlap(pi, pj, Vec2(x[i], y[i]), Vec2(x[j], y[j]), bodies_->length_scale, hint);
  pair.overlapping = geo.kind != geometry::ContactGeometry::Kind::none;
  if (pair.overlapping) {
    const double* inv_d = inv_diameter_.data();
    const PairContact contact{geo.point.x(),
                              geo.point.y(),
                              geo.normal.x(),
                              geo.normal.y(),
                              geo.area,
                              geo.kind == geometry::ContactGeometry::Kind::enclosed,
                              geo.distinct_crossings > 2,
                              pair.i,
                              pair.j,
                              0.5 * (inv_d[pair.i] + inv_d[pair.j])};
    if (fill) {
      fill->put(contact);
    } else {
      geometry_[p] = contact;
      pair_state_[p] = PairState::overlapping;
    }
  }
}

void ContactSearch::Fill::put(const PairContact& contact) {
  const std::size_t k = next++;
  enclosed += contact.enclosed;
  multi_crossing += contact.multi_crossing;
  out->i[k] = contact.i;
  out->j[k] = contact.j;
  out->rx[k] = contact.rx;
  out->ry[k] = contact.ry;
  out->nx[k] = contact.nx;
  out->ny[k] = contact.ny;
  out->area[k] = contact.area;
  out->inv_lc[k] = contact.inv_lc;
}

void ContactSearch::reserve_threads(std::size_t threads, ContactList& out) {
  if (blocks_.size() < threads) blocks_.resize(threads);
  if (thread_pairs_.size() < threads) thread_pairs_.resize(threads);
  if (out.block.size() < threads) out.block.resize(threads);
  if (out.touch.size() < threads * threads) out.touch.resize(threads * threads);
  pair_schedule_.reserve(threads);
  own_contacts_.reserve(threads);
  room_.reserve(threads);
  moved_.reserve(threads);
  candidates_.reserve(threads);
}

void ContactSearch::find(std::span<const double> q, ContactList& out) {
  reserve_threads(static_cast<std::size_t>(max_threads()), out);
  as_team(bodies_->n > kMinParallelItems, [&] {
    find_start(q, out);
    team_barrier();
    find_finish(q, out);
  });
  find_end(out);
}

void ContactSearch::find_start(std::span<const double> q, const ContactList& out) {
  const auto t = static_cast<std::size_t>(thread_index());
  if (t == 0) teams_ = static_cast<std::size_t>(thread_count());
  blocks_[t] = Block{};
  candidates_.mine() = 0;
  if (bodies_->n < 2) return;
  world_vertices_and_staleness(q);
  // This thread's cursor, for the current list (a rebuild resets them all), and what the list has room for,
  // read before anyone can change it (behind the barrier).
  const std::size_t pairs = neighbours_.size();
  pair_schedule_.start_mine(pairs);
  room_.mine() = out.room() >= pairs;
}

void ContactSearch::find_finish(std::span<const double> q, ContactList& out) {
  const auto t = static_cast<std::size_t>(thread_index()), nt = static_cast<std::size_t>(thread_count());
  Block& block = blocks_[t];
  out.block[t] = {0, 0};
  if (bodies_->n < 2) return;
  const bool room = room_.mine();
  Moved moved;  // the two largest distances over all cells
  for (std::size_t s = 0; s < nt; ++s) {
    moved.add(moved_[s].largest);
    moved.add(moved_[s].second);
  }
  const bool stale = !(moved.largest + moved.second <= skin_);
  if (stale) {
    rebuild(q, out);
  } else if (!room) {
    if (t == 0) out.reserve(neighbours_.size());
    team_barrier();
  }
  const double* x = q.data();
  const double* y = x + bodies_->n;
  const double g = bodies_->length_scale;
  const double slack = 0.25 * geometry::kOverlapAreaTolerance * g * g / std::max(bodies_->max_bound_radius, 1e-300);
  // Pairs that clip cost ten times those that do not: each thread tests the pairs of its cells first, in order,
  // and puts their contacts straight into the list, from the entry of its first pair on (room for them: at most
  // one contact a pair); a thread done with its own tests the others' last pairs, into the pairs' own slots.
  const std::size_t start = pair_schedule_.first(t);
  Fill fill{&out, start, 0, 0};
  std::int64_t candidates = 0;
  pair_schedule_.run(64, [&](std::size_t begin, std::size_t end, bool own) {
    Fill* into = own ? &fill : nullptr;
    for (std::size_t p = begin; p < end; ++p) candidates += test_pair(p, x, y, slack, into);
  });
  candidates_.mine() = candidates;
  const std::size_t own = fill.next - start;
  if (nt > 1) {
    own_contacts_.mine() = own;
    team_barrier();
    // The list in pair order, the same whatever the thread count: this thread's contacts go after those of the
    // threads before it, their own and those of their last pairs, which others tested (counted from the pairs'
    // states). Its own move down there, then its last pairs' come from their slots. The entries below belong to
    // the threads before: the second thread's move overwrites nothing another still reads; a later one waits
    // for the moves before it.
    std::size_t offset = 0;
    for (std::size_t u = 0; u < t; ++u)
      offset += own_contacts_[u] + overlapping_pairs(pair_schedule_.split(u), pair_schedule_.end(u));
    for (std::size_t u = 1; u < nt; ++u) {
      if (u == t) {
        out.move_entries(start, offset, own);
        fill.next = offset + own;
        fill_from_slots(pair_schedule_.split(t), pair_schedule_.end(t), fill);
      }
      if (u + 1 < nt) {
        team_barrier();
      }
    }
    if (t == 0) fill_from_slots(pair_schedule_.split(0), pair_schedule_.end(0), fill);
    block.offset = static_cast<std::int64_t>(offset);
  }
  block.enclosed = fill.enclosed;
  block.multi_crossing = fill.multi_crossing;
  const std::size_t first = static_cast<std::size_t>(block.offset);
  block.count = static_cast<std::int64_t>(fill.next - first);
  out.block[t] = {first, fill.next};
  if (nt > 1) set_touch(out, first, fill.next, nt);
}

void ContactSearch::set_touch(ContactList& out, std::size_t first, std::size_t last, std::size_t nt) const {
  const auto t = static_cast<std::size_t>(thread_index());
  const std::size_t n = bodies_->n;
  Range* touch = out.touch.data() + t * nt;
  for (std::size_t u = 0; u < nt; ++u) touch[u] = {last, first};
  const std::int32_t *ci = out.i.data(), *cj = out.j.data();
  for (std::size_t k = first; k < last; ++k) {
    for (const std::int32_t c : {ci[k], cj[k]}) {
      Range& r = touch[owner_of(static_cast<std::size_t>(c), n, nt)];
      r.first = std::min(r.first, k);
      r.last = k + 1;
    }
  }
  for (std::size_t u = 0; u < nt; ++u)
    if (touch[u].first >= touch[u].last) touch[u] = {0, 0};
}

std::size_t ContactSearch::overlapping_pairs(std::size_t first, std::size_t last) const {
  const PairState* state = pair_state_.data();
  std::size_t count = 0;
  for (std::size_t p = first; p < last; ++p) count += state[p] == PairState::overlapping;
  return count;
}

void ContactSearch::fill_from_slots(std::size_t first, std::size_t last, Fill& fill) const {
  const PairState* state = pair_state_.data();
  for (std::size_t p = first; p < last; ++p) {
    if (state[p] == PairState::overlapping) fill.put(geometry_[p]);
  }
}

void ContactSearch::find_end(ContactList& out) {
  std::int64_t total = 0, candidates = 0, enclosed = 0, multi_crossing = 0;
  for (std::size_t b = 0; b < teams_; ++b) {
    total += blocks_[b].count;
    candidates += candidates_[b];
    enclosed += blocks_[b].enclosed;
    multi_crossing += blocks_[b].multi_crossing;
  }
  out.count_ = static_cast<std::size_t>(total);
  out.blocks = teams_;
  out.candidate_pairs = candidates;
  out.enclosed = enclosed;
  out.multi_crossing = multi_crossing;
}

}  // namespace frac::dem
