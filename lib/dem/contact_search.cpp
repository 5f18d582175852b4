#include "dem/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/overlap.hpp"
#include "geometry/separation.hpp"

namespace frac::dem {

ContactSearch::ContactSearch(const mesh::CellMesh& mesh, const Bodies& bodies)
    : mesh_(&mesh), bodies_(&bodies), world_(mesh.vertex.size()), list_(bodies) {
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

// Thread t's part of the first phase: the vertices of its cells in world coordinates, and how far they moved.
void ContactSearch::vertices(std::size_t t, std::size_t nt) {
  blocks_[t] = Block{};
  candidates_[t] = 0;
  const std::size_t n = bodies_->n;
  if (n < 2) return;
  list_.measure_moves(q_, t, nt);
  const double* x = q_.data();
  const double* y = x + n;
  const double* phi = y + n;
  const Range mine = static_range(n, t, nt);
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
  }
}

// Pair p at state (x, y): bounding circles, then the separating edges, then the overlap geometry, its contact
// into `fill`. Cheap rejection first: a slack below eps_A / (r_i + r_j) skips no pair convex_overlap
// would keep, so the order of the tests changes no result, only the time: a pair that overlapped at the last
// search goes straight to clipping; the others try the facing edges that last separated them (cached per
// pair), then the current facing edges, which become the cached ones when they separate. Returns whether
// the bounding circles overlap. Inline, up to the cached edges (what most pairs need); the rest out of line.
inline bool ContactSearch::test_pair(std::size_t p, const double* x, const double* y, double slack, Fill& fill) {
  auto& pair = list_.pairs()[p];
  const auto i = static_cast<std::size_t>(pair.i), j = static_cast<std::size_t>(pair.j);
  const double dx = x[j] - x[i], dy = y[j] - y[i];
  const double reach = bodies_->bound_radius[i] + bodies_->bound_radius[j];
  if (!(dx * dx + dy * dy < reach * reach)) {
    pair.overlapping = false;
    return false;
  }
  // (Each test starts from the vertex that lay deepest at the last one: mostly, three vertices tested.)
  if (!pair.overlapping && (geometry::edge_separates(world_polygon(i), static_cast<std::size_t>(pair.edge_i),
                                                     world_polygon(j), slack, pair.deepest_i) ||
                            geometry::edge_separates(world_polygon(j), static_cast<std::size_t>(pair.edge_j),
                                                     world_polygon(i), slack, pair.deepest_j)))
    return true;
  test_pair_further(p, x, y, slack, fill);
  return true;
}

// test_pair past the cached edges: the current facing edges, then the overlap.
void ContactSearch::test_pair_further(std::size_t p, const double* x, const double* y, double slack, Fill& fill) {
  auto& pair = list_.pairs()[p];
  const auto i = static_cast<std::size_t>(pair.i), j = static_cast<std::size_t>(pair.j);
  const auto pi = world_polygon(i), pj = world_polygon(j);
  if (!pair.overlapping) {
    const Vec2 dc(x[j] - x[i], y[j] - y[i]);
    const auto fi = geometry::facing_edge(pi, dc), fj = geometry::facing_edge(pj, -dc);
    // (A facing edge that is the cached one was just tested.)
    if ((fi != static_cast<std::size_t>(pair.edge_i) && geometry::edge_separates(pi, fi, pj, slack, pair.deepest_i)) ||
        (fj != static_cast<std::size_t>(pair.edge_j) && geometry::edge_separates(pj, fj, pi, slack, pair.deepest_j))) {
      pair.edge_i = static_cast<std::uint8_t>(fi);
      pair.edge_j = static_cast<std::uint8_t>(fj);
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
    fill.put(pair.i, pair.j, geo, 0.5 * (inv_d[pair.i] + inv_d[pair.j]));
  }
}

void ContactSearch::Fill::put(std::int32_t i, std::int32_t j, const geometry::ContactGeometry& geo, double inv_lc) {
  const std::size_t k = next++;
  if (k == out->room()) out->reserve(2 * k + 64);  // (a list only this thread writes while it fills)
  enclosed += geo.kind == geometry::ContactGeometry::Kind::enclosed;
  multi_crossing += geo.distinct_crossings > 2;
  out->i[k] = i;
  out->j[k] = j;
  out->rx[k] = geo.point.x();
  out->ry[k] = geo.point.y();
  out->nx[k] = geo.normal.x();
  out->ny[k] = geo.normal.y();
  out->area[k] = geo.area;
  out->inv_lc[k] = inv_lc;
}

void ContactSearch::reserve_threads(std::size_t threads, ContactList& out) {
  if (blocks_.size() < threads) blocks_.resize(threads);
  if (out.block.size() < threads) out.block.resize(threads);
  if (out.touch.size() < threads * threads) out.touch.resize(threads * threads);
  if (staged_.size() < threads) staged_.resize(threads);
  list_.reserve_threads(threads);
  candidates_.reserve(threads);
}

void ContactSearch::visit_state(StateArchive& archive) {
  list_.visit_state(archive);
  if (!archive.loading()) return;
  StateArchive::Scope scope(archive, "neighbour_list");
  const auto vertices = [&](std::int32_t k) {
    const auto c = static_cast<std::size_t>(k);
    return static_cast<std::size_t>(mesh_->vertex_offset[c + 1] - mesh_->vertex_offset[c]);
  };
  const auto pairs = list_.pairs();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const NeighbourPair& pair = pairs[p];
    const std::size_t ni = vertices(pair.i), nj = vertices(pair.j);
    bool ok = static_cast<std::size_t>(pair.edge_i) < ni && static_cast<std::size_t>(pair.edge_j) < nj &&
              pair.deepest_i < nj && pair.deepest_j < ni;
    for (std::size_t l = 0; l < pair.lines.size; ++l) ok &= pair.lines.label[l] < ni + nj;
    if (!ok) archive.refuse("edge_i", "pair " + std::to_string(p) + " names an edge or vertex its cells do not have");
  }
}

void ContactSearch::bind(std::span<const double> q, ContactList& out) {
  q_ = q;
  out_ = &out;
  reserve_threads(static_cast<std::size_t>(max_threads()), out);
}

Phases ContactSearch::start_phases() {
  Phases p;
  p.add({"contact search: vertices", false, [this](std::size_t t, std::size_t nt) { vertices(t, nt); }, {}});
  return p;
}

Phases ContactSearch::finish_phases() {
  Phases p;
  p.add({"neighbour list: grid", true, [this](std::size_t, std::size_t) { list_.build_grid(q_); },
         [this] { return bodies_->n >= 2 && list_.stale(static_cast<std::size_t>(thread_count())); }});
  p.add({"neighbour list: pairs", false,
         [this](std::size_t t, std::size_t nt) { list_.find_pairs(q_, world_polygons(), t, nt); },
         [this] { return list_.rebuilding(); }});
  p.add({"neighbour list: join", true, [this](std::size_t, std::size_t nt) { list_.join(nt); },
         [this] { return list_.rebuilding(); }});
  p.add({"contact search: pairs", false, [this](std::size_t t, std::size_t nt) { test_pairs(t, nt); }, {}});
  p.add({"contact list: room", true, [this](std::size_t, std::size_t nt) { count(nt); }, {}});
  p.add({"contact list: fill", false, [this](std::size_t t, std::size_t nt) { fill(t, nt); }, {}});
  return p;
}

void ContactSearch::find(std::span<const double> q, ContactList& out) {
  bind(q, out);
  Phases phases = start_phases();
  phases.add(finish_phases());
  phases.run(team_size(bodies_->n > kMinParallelItems));
}

void ContactSearch::test_pairs(std::size_t t, std::size_t nt) {
  if (bodies_->n < 2) return;
  const double* x = q_.data();
  const double* y = x + bodies_->n;
  const double g = bodies_->length_scale;
  const double slack = 0.25 * geometry::kOverlapAreaTolerance * g * g / std::max(bodies_->max_bound_radius, 1e-300);
  // Each thread tests its part of the pairs in order: the first thread puts its contacts straight into the list,
  // the others into lists of their own, copied in behind it once every thread has counted its contacts. Every
  // list grows with its contacts (they are far fewer than the pairs), so the list's room follows the contacts.
  const Range part = balanced_part(t, nt);
  Fill fill{t == 0 ? out_ : &staged_[t], 0, 0, 0};
  std::int64_t candidates = 0;
  // (The contacts of each chunk of pairs counted for the next evaluation's split: this thread's chunks only.)
  const std::size_t pairs = list_.size(), chunks = (pairs + kChunkPairs - 1) / kChunkPairs;
  std::vector<std::uint32_t>& counts = chunk_contacts_[parity_];
  const bool counted = counts.size() == chunks;
  for (std::size_t c = part.first / kChunkPairs; c * kChunkPairs < part.last; ++c) {
    const std::size_t before = fill.next;
    for (std::size_t p = c * kChunkPairs; p < std::min(part.last, (c + 1) * kChunkPairs); ++p)
      candidates += test_pair(p, x, y, slack, fill);
    if (counted) counts[c] = static_cast<std::uint32_t>(fill.next - before);
  }
  candidates_[t] = candidates;
  blocks_[t] = {static_cast<std::int64_t>(fill.next), fill.enclosed, fill.multi_crossing, 0};
}

void ContactSearch::count(std::size_t nt) {
  list_.end_rebuild();  // (every thread has passed the rebuild's phases)
  ContactList& out = *out_;
  std::int64_t total = 0, candidates = 0, enclosed = 0, multi_crossing = 0;
  for (std::size_t b = 0; b < nt; ++b) {
    blocks_[b].offset = total;
    total += blocks_[b].count;
    candidates += candidates_[b];
    enclosed += blocks_[b].enclosed;
    multi_crossing += blocks_[b].multi_crossing;
  }
  // (The first thread's contacts are in the list already, grown as it filled; the others' go in behind them.)
  const auto size = static_cast<std::size_t>(total);
  if (size > out.room()) out.reserve(size + size / 4);
  out.count_ = size;
  // The counts just taken are the next split's; the other array takes the next ones (sized to the list).
  const std::size_t chunks = (list_.size() + kChunkPairs - 1) / kChunkPairs;
  if (chunk_contacts_[parity_].size() != chunks) chunk_contacts_[parity_].assign(chunks, 0);
  parity_ ^= 1;
  if (chunk_contacts_[parity_].size() != chunks) chunk_contacts_[parity_].assign(chunks, 0);
  out.blocks = nt;
  out.candidate_pairs = candidates;
  out.enclosed = enclosed;
  out.multi_crossing = multi_crossing;
}

void ContactSearch::fill(std::size_t t, std::size_t nt) {
  ContactList& out = *out_;
  const Block& block = blocks_[t];
  const auto first = static_cast<std::size_t>(block.offset), own = static_cast<std::size_t>(block.count);
  if (t > 0 && own > 0) out.copy_entries(staged_[t], own, first);
  out.block[t] = {first, first + own};
  if (nt > 1) set_touch(out, t, first, first + own, nt);
}

Range ContactSearch::balanced_part(std::size_t t, std::size_t nt) const {
  // Whole chunks of pairs, so that each chunk's count has one writer; by the weight of the last evaluation's
  // chunks (a pair, and kContactWeight more for each contact it had): the threads then finish together where
  // the contacts crowd. Any split gives the same list (each thread's contacts in pair order, joined in thread
  // order); this one depends on the last evaluation alone, so it is the same in every run.
  const std::size_t pairs = list_.size(), chunks = (pairs + kChunkPairs - 1) / kChunkPairs;
  if (nt == 1) return {0, pairs};
  const std::vector<std::uint32_t>& last = chunk_contacts_[parity_ ^ 1];
  const bool known = last.size() == chunks;  // (not after a rebuild: then by the pairs alone)
  const auto weight = [&](std::size_t c) {
    const double w = static_cast<double>(std::min(pairs, (c + 1) * kChunkPairs) - c * kChunkPairs);
    return known ? w + kContactWeight * static_cast<double>(last[c]) : w;
  };
  double total = 0;
  for (std::size_t c = 0; c < chunks; ++c) total += weight(c);
  // Thread u's part starts at the first chunk whose weight before it reaches total · u / nt.
  const auto start = [&](std::size_t u) {
    if (u == 0) return std::size_t{0};
    if (u >= nt) return chunks;
    const double goal = total * static_cast<double>(u) / static_cast<double>(nt);
    double before = 0;
    std::size_t c = 0;
    while (c < chunks && before + 0.5 * weight(c) < goal) before += weight(c++);
    return c;
  };
  return {std::min(pairs, start(t) * kChunkPairs), std::min(pairs, start(t + 1) * kChunkPairs)};
}

void ContactSearch::set_touch(ContactList& out, std::size_t t, std::size_t first, std::size_t last,
                              std::size_t nt) const {
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

}  // namespace frac::dem
