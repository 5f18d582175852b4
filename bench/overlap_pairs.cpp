// The overlap of the neighbour pairs of one frame of a dem-run output, timed two ways: by clipping (with the
// contact search's hint: the facing edges and their reaches), and from the lines that each pair kept from
// the evaluation before (the contact search's cache, geometry::OverlapLines), which is how dem-run computes
// most overlaps. Both give the same bits; the program checks it.
// Usage: overlap-pairs RUN.h5 [FRAME (default -1, the last)] [PASSES (default 2000)]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "geometry/overlap.hpp"
#include "geometry/separation.hpp"
#include "io/hdf5.hpp"
#include "io/mesh_io.hpp"
#include "io/run_io.hpp"

namespace {

using frac::geometry::ContactGeometry;
using frac::geometry::Vec2;

struct Pair {
  std::size_t i, j;
  frac::geometry::OverlapHint hint;
};

bool same_bits(const ContactGeometry& a, const ContactGeometry& b) {
  return a.kind == b.kind && a.area == b.area && a.crossings == b.crossings && a.p1 == b.p1 && a.p2 == b.p2 &&
         a.point == b.point && a.normal == b.normal;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: overlap-pairs RUN.h5 [FRAME] [PASSES]\n");
    return 2;
  }
  try {
    const auto root = frac::io::open_input(argv[1]);
    const long long frame_index = argc > 2 ? std::atoll(argv[2]) : -1;
    const int passes = argc > 3 ? std::atoi(argv[3]) : 2000;
    const auto mesh = frac::io::read_cell_mesh(root);
    const auto frame = frac::io::read_frame(root, frame_index);
    const std::size_t n = mesh.cells();
    const double g = mesh.spacing;

    // The cells in the frame, and their bounding radii.
    std::vector<std::vector<Vec2>> world(n);
    std::vector<Vec2> centre(n);
    std::vector<double> radius(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      centre[k] = Vec2(frame.position[2 * k], frame.position[2 * k + 1]);
      const double c = std::cos(frame.angle[k]), s = std::sin(frame.angle[k]);
      for (const Vec2& p : mesh.polygon(k)) {
        world[k].push_back(centre[k] + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
        radius[k] = std::max(radius[k], p.norm());
      }
    }
    // The pairs the contact search would clip: bounding circles overlap, and no facing edge separates them.
    const double largest = *std::max_element(radius.begin(), radius.end());
    const double slack = 0.25 * frac::geometry::kOverlapAreaTolerance * g * g / largest;
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if ((centre[j] - centre[i]).norm() >= radius[i] + radius[j]) continue;
        frac::geometry::OverlapHint hint;
        hint.edge_i = frac::geometry::facing_edge(world[i], centre[j] - centre[i]);
        hint.edge_j = frac::geometry::facing_edge(world[j], centre[i] - centre[j]);
        if (frac::geometry::edge_separates(world[i], hint.edge_i, world[j], slack) ||
            frac::geometry::edge_separates(world[j], hint.edge_j, world[i], slack))
          continue;
        hint.reach_i = frac::geometry::edge_reach(mesh.polygon(i), hint.edge_i);
        hint.reach_j = frac::geometry::edge_reach(mesh.polygon(j), hint.edge_j);
        pairs.push_back({i, j, hint});
      }
    }
    if (pairs.empty()) throw std::runtime_error("no overlapping pairs in this frame");

    // One pass with the caches filled as the contact search fills them; the results bit for bit.
    std::vector<frac::geometry::OverlapLines> lines(pairs.size());
    std::size_t overlapping = 0, cached = 0;
    for (int warm = 0; warm < 2; ++warm) {
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const Pair& q = pairs[p];
        frac::geometry::OverlapHint hint = q.hint;
        hint.lines = &lines[p];
        const bool had = lines[p].size >= 3;
        const auto fast = frac::geometry::convex_overlap(world[q.i], world[q.j], centre[q.i], centre[q.j], g, hint);
        const auto clipped =
            frac::geometry::convex_overlap(world[q.i], world[q.j], centre[q.i], centre[q.j], g, q.hint);
        if (!same_bits(fast, clipped)) throw std::runtime_error("cached and clipped results differ");
        if (warm == 1) {
          overlapping += fast.kind != ContactGeometry::Kind::none;
          cached += had && lines[p].size >= 3;
        }
      }
    }

    // Median over 5 rounds of `passes` passes over the pairs of a class (all; those whose lines were kept, the
    // regular overlaps; the others, which clip: irregular overlaps, the thin slivers among them, and no overlap).
    std::vector<std::size_t> all, regular, other;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      all.push_back(p);
      (lines[p].size >= 3 ? regular : other).push_back(p);
    }
    auto time_ns = [&](bool use_lines, const std::vector<std::size_t>& which) {
      std::vector<double> rounds;
      double sink = 0.0;
      for (int r = 0; r < 5; ++r) {
        const auto start = std::chrono::steady_clock::now();
        for (int pass = 0; pass < passes; ++pass) {
          for (const std::size_t p : which) {
            const Pair& q = pairs[p];
            frac::geometry::OverlapHint hint = q.hint;
            if (use_lines) hint.lines = &lines[p];
            sink += frac::geometry::convex_overlap(world[q.i], world[q.j], centre[q.i], centre[q.j], g, hint).area;
          }
        }
        const std::chrono::duration<double, std::nano> t = std::chrono::steady_clock::now() - start;
        const auto count = static_cast<double>(std::max<std::size_t>(which.size(), 1));
        rounds.push_back(t.count() / (static_cast<double>(passes) * count));
      }
      std::sort(rounds.begin(), rounds.end());
      if (!(sink >= 0.0)) std::fprintf(stderr, "(sum %g)\n", sink);  // keeps the work
      return rounds[2];
    };
    const double clip = time_ns(false, all), from_lines = time_ns(true, all);
    const double regular_ns = time_ns(true, regular), other_ns = time_ns(true, other);
    std::printf(
        "| pairs clipped | overlapping | from cached lines | clipping, ns per pair | cached lines, ns per pair "
        "| ratio | kept lines, ns | the others, ns |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    std::printf("| %zu | %zu | %.1f %% | %.1f | %.1f | %.2f | %.1f | %.1f |\n", pairs.size(), overlapping,
                100.0 * static_cast<double>(cached) / static_cast<double>(pairs.size()), clip, from_lines,
                from_lines / clip, regular_ns, other_ns);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "overlap-pairs: %s\n", e.what());
    return 1;
  }
}
