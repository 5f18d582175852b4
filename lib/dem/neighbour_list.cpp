#include "dem/neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/separation.hpp"

namespace frac::dem {
using geometry::Vec2;
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

NeighbourList::NeighbourList(const Bodies& bodies)
    : bodies_(&bodies), skin_(0.2 * bodies.length_scale), cell_of_(bodies.n), sorted_(bodies.n), grid_body_(bodies.n) {}

void NeighbourList::reserve_threads(std::size_t threads) {
  if (thread_pairs_.size() < threads) thread_pairs_.resize(threads);
  moved_.reserve(threads);
}

// The two largest distances this thread's cells' centroids have moved since the build, into its slot (NaN
// counts as infinitely far). A polygon never leaves its bounding circle about its centroid, whatever it turns,
// so a pair left out of the list (circles more than the skin apart) cannot overlap while the two largest
// distances over all cells sum to at most the skin.
void NeighbourList::measure_moves(std::span<const double> q, std::size_t t, std::size_t nt) {
  const std::size_t n = bodies_->n;
  if (ref_.size() != q.size()) {
    moved_[t] = {kInfinity, kInfinity};
    return;
  }
  const double* x = q.data();
  const double* y = x + n;
  const double* ref = ref_.data();
  Moved moved;
  const Range mine = static_range(n, t, nt);
  for (std::size_t k = mine.first; k < mine.last; ++k) {
    const double dx = x[k] - ref[k], dy = y[k] - ref[n + k];
    const double d2 = dx * dx + dy * dy;
    if (!(d2 <= moved.second * moved.second)) moved.add(std::isnan(d2) ? kInfinity : std::sqrt(d2));  // (rarely)
  }
  moved_[t] = moved;
}

bool NeighbourList::stale(std::size_t nt) const {
  Moved moved;
  for (std::size_t t = 0; t < nt; ++t) {
    moved.add(moved_[t].largest);
    moved.add(moved_[t].second);
  }
  return !(moved.largest + moved.second <= skin_);
}

void NeighbourList::build_grid(std::span<const double> q) {
  const std::size_t n = bodies_->n;
  const double* x = q.data();
  const double* y = x + n;
  ++rebuilds_;
  rebuilding_ = true;
  ref_.assign(q.begin(), q.end());
  // The old list, indexed by its first cell, so that a pair found again keeps what it has learnt (its
  // separating edges, whether it overlapped, the lines of its overlap): less work. (The kept facing edge
  // sets the clip order, which only an irregular overlap's result depends on, at round-off.)
  std::swap(previous_, pairs_);
  pairs_.clear();
  pairs_.reserve(previous_.size() + previous_.size() / 16);  // (the first thread's part, then the others' behind it)
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

void NeighbourList::find_pairs(std::span<const double> q, WorldPolygons world, std::size_t t, std::size_t nt) {
  const std::size_t n = bodies_->n;
  const double* x = q.data();
  const double* y = x + n;
  // The pairs (i, j > i) in order of i, then of j: threads take contiguous ranges of i (in thread order) into
  // their own buffers, joined in thread order. The list, and so the contacts' order in which every cell sums their
  // forces, is a function of the cells' indices alone: not of the grid, the thread count or (split over ranks,
  // with indices as global ids) the rank count.
  auto& buf = t == 0 ? pairs_ : thread_pairs_[t];  // (build_grid cleared pairs_)
  if (t > 0) buf.clear();
  const std::size_t gx = grid_x_, gy = grid_y_;
  const GridBody* body = grid_body_.data();
  // use(j, dx, dy) for every j > i whose bounding circle comes within the skin of i's, in the order of the scan.
  auto pairs_of = [&](std::size_t i, auto&& use) {
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
          if (dx * dx + dy * dy < reach * reach) use(j, dx, dy);
        }
      }
    }
  };
  // A pair found again keeps what it learnt; a new one starts from its facing edges.
  auto keep_pairs_of = [&](std::size_t i) {
    const std::size_t first_of_i = buf.size();
    pairs_of(i, [&](std::size_t j, double dx, double dy) {
      const auto* const begin = previous_.data() + previous_first_[i];
      const auto* const last = previous_.data() + previous_first_[i + 1];
      const auto* const known =
          std::find_if(begin, last, [&](const NeighbourPair& o) { return o.j == static_cast<std::int32_t>(j); });
      if (known != last) {
        buf.push_back(*known);
        return;
      }
      const Vec2 dij(dx, dy);
      buf.push_back({static_cast<std::int32_t>(i),
                     static_cast<std::int32_t>(j),
                     static_cast<std::uint8_t>(geometry::facing_edge(world(i), dij)),
                     static_cast<std::uint8_t>(geometry::facing_edge(world(j), -dij)),
                     false,
                     0,
                     0,
                     {}});
    });
    std::sort(buf.begin() + static_cast<std::ptrdiff_t>(first_of_i), buf.end(),
              [](const NeighbourPair& a, const NeighbourPair& b) { return a.j < b.j; });
  };
  if (gx > 0) {
    const std::size_t first = n * t / nt, last = n * (t + 1) / nt;
    if (previous_.empty()) {  // (the first build, with no list to size it by: counted first, allocated once)
      std::size_t count = 0;
      for (std::size_t i = first; i < last; ++i) pairs_of(i, [&](std::size_t, double, double) { ++count; });
      buf.reserve(count);
    } else if (t > 0) {  // (sized by the old list's pairs of these cells: grown by doubling, it could take twice)
      const auto before = static_cast<std::size_t>(previous_first_[last] - previous_first_[first]);
      buf.reserve(before + before / 16 + 64);
    }
    for (std::size_t i = first; i < last; ++i) keep_pairs_of(i);
  }
}

void NeighbourList::join(std::size_t nt) {
  std::vector<NeighbourPair>().swap(previous_);  // (read by no thread now: freed before the list may grow)
  for (std::size_t b = 1; b < nt; ++b) {
    pairs_.insert(pairs_.end(), thread_pairs_[b].begin(), thread_pairs_[b].end());
    std::vector<NeighbourPair>().swap(thread_pairs_[b]);
  }
}

void NeighbourList::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "neighbour_list");
  const std::size_t n = bodies_->n;
  archive.value("rebuilds", rebuilds_);
  archive.array("reference_q", ref_);
  std::size_t pairs = pairs_.size();
  archive.value("pairs", pairs);
  if (archive.loading()) {
    if (ref_.size() != 3 * n && !ref_.empty()) archive.refuse("reference_q", "not one position per coordinate");
    if (pairs > n * (n - 1) / 2) archive.refuse("pairs", "more pairs than the cells make");
    pairs_.assign(pairs, NeighbourPair{});
    previous_.clear();
  }
  archive.field("i", pairs_, &NeighbourPair::i);
  archive.field("j", pairs_, &NeighbourPair::j);
  archive.field("edge_i", pairs_, &NeighbourPair::edge_i);
  archive.field("edge_j", pairs_, &NeighbourPair::edge_j);
  archive.field("overlapping", pairs_, &NeighbourPair::overlapping);
  archive.field("deepest_i", pairs_, &NeighbourPair::deepest_i);
  archive.field("deepest_j", pairs_, &NeighbourPair::deepest_j);
  // The cached overlap lines: their count and labels, 1 + 8 bytes a pair.
  constexpr std::size_t kLabels = std::tuple_size_v<decltype(geometry::OverlapLines::label)>;
  std::vector<std::uint8_t> lines(pairs * (1 + kLabels));
  if (!archive.loading())
    for (std::size_t p = 0; p < pairs; ++p) {
      lines[p * (1 + kLabels)] = pairs_[p].lines.size;
      std::copy(pairs_[p].lines.label.begin(), pairs_[p].lines.label.end(),
                lines.begin() + static_cast<std::ptrdiff_t>(p * (1 + kLabels) + 1));
    }
  archive.array("lines", lines, pairs * (1 + kLabels));
  if (!archive.loading()) return;
  for (std::size_t p = 0; p < pairs; ++p) {
    NeighbourPair& pair = pairs_[p];
    if (pair.i < 0 || pair.j <= pair.i || static_cast<std::size_t>(pair.j) >= n)
      archive.refuse("i", "pair " + std::to_string(p) + " is not two cells i < j of the mesh");
    pair.lines.size = lines[p * (1 + kLabels)];
    if (pair.lines.size > kLabels)
      archive.refuse("lines", "pair " + std::to_string(p) + ": more lines than a cache holds");
    std::copy_n(lines.begin() + static_cast<std::ptrdiff_t>(p * (1 + kLabels) + 1), kLabels, pair.lines.label.begin());
  }
}

}  // namespace frac::dem
