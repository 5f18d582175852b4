// Meshes: the Voronoi tessellation behind the vectorizable random lattice (polygon-dem.md §1-2), the
// triangular lattice of the rubber sheet (rubber-lattice.md §6), and their checker.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "mesh/cell_overlaps.hpp"
#include "mesh/check.hpp"
#include "mesh/random_lattice.hpp"
#include "mesh/triangular_lattice.hpp"
#include "mesh/voronoi.hpp"

namespace {

using frac::geometry::Vec2;
using frac::mesh::CellMesh;
using frac::mesh::NodeMesh;
using frac::mesh::RandomLatticeOptions;
using frac::mesh::TriangularLatticeOptions;

RandomLatticeOptions rect(std::int64_t nx, std::int64_t ny, double w, double h, double disorder, std::uint64_t seed) {
  RandomLatticeOptions o;
  o.shape = "rect";
  o.nx = nx;
  o.ny = ny;
  o.width = w;
  o.height = h;
  o.disorder = disorder;
  o.seed = seed;
  return o;
}

std::vector<int> beams_per_cell(const CellMesh& m) {
  std::vector<int> n(m.cells(), 0);
  for (const auto& b : m.beam) {
    ++n[static_cast<std::size_t>(b[0])];
    ++n[static_cast<std::size_t>(b[1])];
  }
  return n;
}

// Expects `f` to throw UsageError whose message names `option`.
template <class F>
void expect_usage_error(F f, const std::string& option) {
  try {
    f();
    ADD_FAILURE() << "no UsageError for " << option;
  } catch (const frac::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Voronoi

TEST(Voronoi, TwoSitesSplitTheBox) {
  const std::vector<Vec2> sites{{0.25, 0.5}, {0.75, 0.5}};
  const auto vd = frac::mesh::voronoi_in_box(sites, {0.0, 0.0, 1.0, 1.0}, 1e-12);
  ASSERT_EQ(vd.cell.size(), 2u);
  // Two half boxes; the shared side is the bisector x = 1/2 of length 1. Round-off only: 1e-14.
  EXPECT_NEAR(frac::geometry::signed_area(vd.cell[0]), 0.5, 1e-14);
  EXPECT_NEAR(frac::geometry::signed_area(vd.cell[1]), 0.5, 1e-14);
  EXPECT_EQ(vd.cell[0].size(), 4u);
  ASSERT_EQ(vd.neighbour.size(), 1u);
  EXPECT_EQ(vd.neighbour[0][0], 0);
  EXPECT_EQ(vd.neighbour[0][1], 1);
  EXPECT_NEAR(vd.shared_side[0], 1.0, 1e-14);
}

TEST(Voronoi, SiteOutsideTheBoxHasAnEmptyCell) {
  const std::vector<Vec2> sites{{0.5, 0.5}, {2.0, 0.5}};
  const auto vd = frac::mesh::voronoi_in_box(sites, {0.0, 0.0, 1.0, 1.0}, 1e-12);
  EXPECT_NEAR(frac::geometry::signed_area(vd.cell[0]), 1.0, 1e-14);
  EXPECT_TRUE(vd.cell[1].empty());
  EXPECT_TRUE(vd.neighbour.empty());
}

TEST(Voronoi, DuplicateSitesAreRejected) {
  const std::vector<Vec2> sites{{0.5, 0.5}, {0.5, 0.5}};
  EXPECT_THROW(frac::mesh::voronoi_in_box(sites, {0.0, 0.0, 1.0, 1.0}, 1e-12), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Random lattice, rectangle

TEST(RandomLattice, RectangleTilesTheBoxExactly) {
  for (const std::uint64_t seed : {1u, 2u, 3u, 17u, 12345u}) {
    const auto m = frac::mesh::make_random_lattice(rect(40, 20, 0.40, 0.20, 1.0, seed));
    ASSERT_EQ(m.cells(), 800u);
    EXPECT_EQ(m.shape, "rect");
    EXPECT_DOUBLE_EQ(m.spacing, 0.01);
    EXPECT_EQ(m.bounds, (std::array<double, 4>{0.0, 0.0, 0.40, 0.20}));
    // The cells tile the box: the sum of 800 areas, each exact to ~1e-16 relative, is W H to 1e-12.
    double total = 0.0;
    for (const double a : m.area) total += a;
    EXPECT_NEAR(total, 0.40 * 0.20, 1e-12 * 0.40 * 0.20) << "seed " << seed;
    for (std::size_t k = 0; k < m.cells(); ++k) {
      // Convex and counter-clockwise; 1e-12 on the sine of the turn angle is pure round-off.
      ASSERT_TRUE(frac::geometry::is_convex_ccw(m.polygon(k), 1e-12)) << "cell " << k << " seed " << seed;
      for (const auto& v : m.world_polygon(k)) {
        // Clipped to the box: vertices inside it up to round-off (1e-15 m on coordinates <= 0.4 m).
        ASSERT_GE(v.x(), -1e-15);
        ASSERT_LE(v.x(), 0.40 + 1e-15);
        ASSERT_GE(v.y(), -1e-15);
        ASSERT_LE(v.y(), 0.20 + 1e-15);
      }
    }
    const auto report = frac::mesh::check_cell_mesh(m);
    EXPECT_TRUE(report.ok()) << "seed " << seed << ": " << (report.failures.empty() ? "" : report.failures[0]);
    // Cells are numbered in grid order: cell j nx + i lies in (or near: a <= g) grid cell (i, j).
    for (std::size_t k = 0; k < m.cells(); ++k) {
      const double i = static_cast<double>(k % 40), j = static_cast<double>(k / 40);
      EXPECT_LT(std::abs(m.centroid[k].x() - (i + 0.5) * 0.01), 0.02);
      EXPECT_LT(std::abs(m.centroid[k].y() - (j + 0.5) * 0.01), 0.02);
    }
  }
}

TEST(RandomLattice, ZeroDisorderGivesTheSquareGrid) {
  const auto m = frac::mesh::make_random_lattice(rect(40, 20, 0.40, 0.20, 0.0, 1));
  ASSERT_EQ(m.cells(), 800u);
  const double g = 0.01;
  for (std::size_t k = 0; k < m.cells(); ++k) {
    // Every cell a g x g square (the four cocircular Voronoi vertices merged into one): the area is
    // exact to round-off, 1e-12 relative; 4 vertices.
    EXPECT_NEAR(m.area[k], g * g, 1e-12 * g * g) << "cell " << k;
    EXPECT_EQ(m.polygon(k).size(), 4u) << "cell " << k;
    EXPECT_NEAR(m.second_moment[k], g * g * g * g / 6.0, 1e-12 * g * g * g * g);
  }
  // Beams only between edge-sharing grid neighbours (no diagonals), all of length g and section g.
  for (std::size_t e = 0; e < m.beams(); ++e) {
    const auto [a, b] = m.beam[e];
    const bool horizontal = b == a + 1 && a / 40 == b / 40;
    const bool vertical = b == a + 40;
    EXPECT_TRUE(horizontal || vertical) << a << " " << b;
    EXPECT_NEAR(m.beam_length[e], g, 1e-12);
    EXPECT_NEAR(m.beam_section[e], g, 1e-12);
  }
  EXPECT_EQ(m.beams(), static_cast<std::size_t>(39 * 20 + 40 * 19));
  const auto n = beams_per_cell(m);
  for (std::size_t k = 0; k < m.cells(); ++k) {
    const auto i = k % 40, j = k / 40;
    const int edges = (i == 0 || i == 39) + (j == 0 || j == 19);
    EXPECT_EQ(n[k], 4 - edges) << "cell " << k;  // 4 inside, 3 on a side, 2 in a corner
  }
  EXPECT_TRUE(frac::mesh::check_cell_mesh(m).ok());
}

TEST(RandomLattice, TinyDisorderStillTiles) {
  // Near-square tessellations have many Voronoi vertices split by ~disorder * g. Those closer than
  // the merge tolerance (1e-9 g) are merged once for all cells, so neighbours keep identical vertices
  // and the areas still add up to W H to round-off (1e-12 relative; merging per cell left gaps of
  // ~1e-10). Larger splits stay as short sides, whose beams are dropped below 1e-6 g.
  for (const double disorder : {1e-10, 1e-9, 3e-9, 1e-7, 1e-5}) {
    const auto m = frac::mesh::make_random_lattice(rect(60, 40, 0.6, 0.4, disorder, 21));
    double total = 0.0;
    for (const double a : m.area) total += a;
    EXPECT_NEAR(total, 0.24, 1e-12 * 0.24) << "disorder " << disorder;
    const auto report = frac::mesh::check_cell_mesh(m);
    EXPECT_TRUE(report.ok()) << "disorder " << disorder << ": " << (report.ok() ? "" : report.failures[0]);
    for (const double s : m.beam_section) EXPECT_GE(s, 1e-6 * 0.01);
  }
}

// Neighbour counts of inner cells. polygon-dem.md §1: the mean is 6; for a = g, 3 <= n <= 11; for
// a <= g/2, 4 <= n <= 8. Inner: 5 grid cells or more from the sides (neighbours lie at most 3 cells
// away, so these cells do not feel the box).
std::map<int, std::int64_t> inner_histogram(const CellMesh& m, std::int64_t nx, std::int64_t ny, double* mean) {
  const auto n = beams_per_cell(m);
  std::map<int, std::int64_t> h;
  double sum = 0.0;
  std::int64_t count = 0;
  for (std::int64_t j = 5; j < ny - 5; ++j) {
    for (std::int64_t i = 5; i < nx - 5; ++i) {
      const int d = n[static_cast<std::size_t>(j * nx + i)];
      ++h[d];
      sum += d;
      ++count;
    }
  }
  *mean = sum / static_cast<double>(count);
  return h;
}

TEST(RandomLattice, NeighbourCountsFollowTheNote) {
  for (const double disorder : {1.0, 0.5}) {
    const auto m = frac::mesh::make_random_lattice(rect(200, 200, 2.0, 2.0, disorder, 7));
    double mean = 0.0;
    const auto h = inner_histogram(m, 200, 200, &mean);
    std::cout << "disorder " << disorder << ": beams per inner cell (mean " << mean << "):";
    for (const auto& [d, c] : h) std::cout << " " << d << ":" << c;
    std::cout << "\n";
    const int lo = disorder == 1.0 ? 3 : 4, hi = disorder == 1.0 ? 11 : 8;
    EXPECT_GE(h.begin()->first, lo);
    EXPECT_LE(h.rbegin()->first, hi);
    // 36 100 inner cells; the count has a standard deviation ~1.3 and Euler's relation pins the
    // mean of a large patch to 6 (beams dropped below 1e-6 g are a ~1e-6 effect): 0.05 is ample.
    EXPECT_NEAR(mean, 6.0, 0.05);
    if (disorder == 1.0) {
      // P(6) ~ 0.37 in the note (120 000 cells); 36 100 cells give a standard error ~0.003.
      EXPECT_NEAR(static_cast<double>(h.at(6)) / 36100.0, 0.37, 0.03);
    }
    EXPECT_TRUE(frac::mesh::check_cell_mesh(m).ok());
  }
}

TEST(RandomLattice, DiscRegionStaysInTheBox) {
  // Disc region with a = g: sites can leave their grid cell (and the box, where they are mirrored).
  auto o = rect(30, 20, 0.30, 0.20, 1.0, 5);
  o.disorder_region = "disc";
  const auto m = frac::mesh::make_random_lattice(o);
  ASSERT_EQ(m.cells(), 600u);
  EXPECT_EQ(m.disorder_region, "disc");
  double total = 0.0;
  for (const double a : m.area) total += a;
  EXPECT_NEAR(total, 0.30 * 0.20, 1e-12 * 0.30 * 0.20);
  EXPECT_TRUE(frac::mesh::check_cell_mesh(m).ok());
}

// ---------------------------------------------------------------------------------------------
// Random lattice, disc

TEST(RandomLattice, DiscOf1100Cells) {
  const double r = 0.20, g = std::sqrt(std::numbers::pi * r * r / 1100.0);
  EXPECT_NEAR(g * g, 1.14e-4, 0.005e-4);  // mean polygon area ~1.14 cm^2 (polygon-dem.md §1)
  for (const std::uint64_t seed : {3u, 4u, 5u}) {
    RandomLatticeOptions o;
    o.shape = "disc";
    o.diameter = 0.40;
    o.cells = 1100;
    o.seed = seed;
    const auto m = frac::mesh::make_random_lattice(o);
    EXPECT_NEAR(m.spacing, g, 1e-15);
    EXPECT_EQ(m.bounds, (std::array<double, 4>{-r, -r, r, r}));
    // The count fluctuates only along the rim (~2 pi R / g = 118 cells): 5 % (55 cells) is generous.
    EXPECT_NEAR(static_cast<double>(m.cells()), 1100.0, 55.0) << "seed " << seed;
    for (std::size_t k = 0; k < m.cells(); ++k) {
      EXPECT_LE(m.centroid[k].norm(), r);
      // A Voronoi vertex lies within sqrt(2) g of its site (every empty circle of the lattice has a
      // radius below sqrt(2) g) and so does the centroid: vertices lie within R + 2 sqrt(2) g.
      for (const auto& v : m.world_polygon(k)) EXPECT_LE(v.norm(), r + 2.0 * std::numbers::sqrt2 * g);
    }
    const auto report = frac::mesh::check_cell_mesh(m);
    EXPECT_TRUE(report.ok()) << "seed " << seed;
    // The kept cells are whole Voronoi cells, so their mean area is g^2 up to the rim's keep-or-drop
    // decisions (~1 %): 3 % tolerance.
    double total = 0.0;
    for (const double a : m.area) total += a;
    EXPECT_NEAR(total / static_cast<double>(m.cells()), g * g, 0.03 * g * g) << "seed " << seed;
    if (seed == 3) std::cout << report.summary;
  }
}

// ---------------------------------------------------------------------------------------------
// Reproducibility and options

TEST(RandomLattice, SameSeedSameMeshDifferentSeedDifferentMesh) {
  const auto a = frac::mesh::make_random_lattice(rect(30, 30, 0.3, 0.3, 1.0, 99));
  const auto b = frac::mesh::make_random_lattice(rect(30, 30, 0.3, 0.3, 1.0, 99));
  const auto c = frac::mesh::make_random_lattice(rect(30, 30, 0.3, 0.3, 1.0, 100));
  EXPECT_EQ(a.vertex_offset, b.vertex_offset);
  EXPECT_EQ(a.vertex, b.vertex);  // bit-identical: == on every double
  EXPECT_EQ(a.centroid, b.centroid);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.second_moment, b.second_moment);
  EXPECT_EQ(a.beam, b.beam);
  EXPECT_EQ(a.beam_length, b.beam_length);
  EXPECT_EQ(a.beam_section, b.beam_section);
  EXPECT_NE(a.centroid, c.centroid);
  EXPECT_NE(a.area, c.area);
}

TEST(RandomLattice, BadOptionsNameTheOption) {
  using frac::mesh::make_random_lattice;
  auto good = rect(4, 2, 0.4, 0.2, 1.0, 1);
  EXPECT_NO_THROW(make_random_lattice(good));
  auto o = good;
  o.shape = "hexagon";
  expect_usage_error([&] { make_random_lattice(o); }, "--shape");
  o = good;
  o.width = -1.0;
  expect_usage_error([&] { make_random_lattice(o); }, "--size");
  o = good;
  o.height = std::nan("");
  expect_usage_error([&] { make_random_lattice(o); }, "--size");
  o = good;
  o.nx = 0;
  expect_usage_error([&] { make_random_lattice(o); }, "--cells");
  o = good;
  o.nx = 5;  // 0.4 / 5 != 0.2 / 2: cells not square
  expect_usage_error([&] { make_random_lattice(o); }, "--cells");
  o = good;
  o.disorder = 1.5;
  expect_usage_error([&] { make_random_lattice(o); }, "--disorder");
  o = good;
  o.disorder_region = "circle";
  expect_usage_error([&] { make_random_lattice(o); }, "--disorder-region");
  RandomLatticeOptions d;
  d.shape = "disc";
  d.diameter = 0.0;
  d.cells = 10;
  expect_usage_error([&] { make_random_lattice(d); }, "--diameter");
  d.diameter = 0.4;
  d.cells = 0;
  expect_usage_error([&] { make_random_lattice(d); }, "--cells");
}

TEST(RandomLattice, OptionsTheMeshIgnoresAreRefused) {
  using frac::mesh::refuse_ignored_options;
  auto o = rect(4, 2, 0.4, 0.2, 1.0, 1);
  EXPECT_NO_THROW(refuse_ignored_options(o, {"shape", "size", "cells", "seed", "disorder", "disorder-region"}));
  expect_usage_error([&] { refuse_ignored_options(o, {"diameter"}); }, "--diameter: applies to --shape disc");
  o.shape = "disc";
  EXPECT_NO_THROW(refuse_ignored_options(o, {"shape", "diameter", "cells"}));
  expect_usage_error([&] { refuse_ignored_options(o, {"size"}); }, "--size: applies to --shape rect");
  o.disorder = 0;  // (a sweep over the disorder at one seed passes both at every level)
  EXPECT_NO_THROW(refuse_ignored_options(o, {"disorder", "min-section", "seed", "disorder-region"}));
}

// ---------------------------------------------------------------------------------------------
// Checker

TEST(MeshCheck, DetectsBrokenCellMeshes) {
  const auto good = frac::mesh::make_random_lattice(rect(10, 10, 0.1, 0.1, 1.0, 4));
  const auto report = frac::mesh::check_cell_mesh(good);
  ASSERT_TRUE(report.ok());
  EXPECT_NE(report.summary.find("cells: 100"), std::string::npos) << report.summary;
  std::int64_t total = 0;
  for (const auto& [d, c] : report.neighbour_count) total += c;
  EXPECT_EQ(total, 100);

  auto has = [](const frac::mesh::MeshReport& r, const std::string& kind) {
    for (const auto& f : r.failures) {
      if (f.rfind(kind, 0) == 0) return true;
    }
    return false;
  };

  auto cw = good;  // clockwise polygon
  std::reverse(cw.vertex.begin() + cw.vertex_offset[5], cw.vertex.begin() + cw.vertex_offset[6]);
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(cw), "convex"));

  auto dup = good;  // duplicated beam
  dup.beam.insert(dup.beam.begin() + 3, dup.beam[3]);
  dup.beam_length.insert(dup.beam_length.begin() + 3, dup.beam_length[3]);
  dup.beam_section.insert(dup.beam_section.begin() + 3, dup.beam_section[3]);
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(dup), "beam duplicate"));

  auto section = good;  // wrong section
  section.beam_section[7] *= 1.1;
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(section), "beam section"));

  auto length = good;  // wrong l0
  length.beam_length[2] += 1e-4;
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(length), "beam length"));

  auto area = good;  // area inconsistent with the vertices
  area.area[9] *= 1.01;
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(area), "area"));

  auto shifted = good;  // centroid not at the body origin
  for (auto& v : shifted.vertex) v.x() += 1e-5;
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(shifted), "centroid"));

  auto unrelated = good;  // a beam between cells that share no side
  unrelated.beam.push_back({0, 99});
  unrelated.beam_length.push_back((good.centroid[99] - good.centroid[0]).norm());
  unrelated.beam_section.push_back(0.01);
  EXPECT_TRUE(has(frac::mesh::check_cell_mesh(unrelated), "beam section"));

  EXPECT_FALSE(frac::mesh::check_cell_mesh(CellMesh{}).ok());
}

TEST(MeshCheck, DetectsBrokenNodeMeshes) {
  TriangularLatticeOptions o;
  o.nx = 6;
  o.ny = 5;
  o.spacing = 1e-3;
  const auto good = frac::mesh::make_triangular_lattice(o);
  ASSERT_TRUE(frac::mesh::check_node_mesh(good).ok());
  auto bad = good;
  bad.bond_length[4] *= 1.01;
  EXPECT_FALSE(frac::mesh::check_node_mesh(bad).ok());
  bad = good;
  bad.bond.push_back(bad.bond.back());
  bad.bond_length.push_back(bad.bond_length.back());
  bad.intact.push_back(1);
  EXPECT_FALSE(frac::mesh::check_node_mesh(bad).ok());
  bad = good;
  std::swap(bad.bond[0][0], bad.bond[0][1]);
  EXPECT_FALSE(frac::mesh::check_node_mesh(bad).ok());
}

// The first failure of a report (what a tool's message shows first), or "(valid)".
std::string first_failure(const frac::mesh::MeshReport& r) { return r.failures.empty() ? "(valid)" : r.failures[0]; }

TEST(MeshCheck, NonFiniteValuesAreReportedFirstAndAlone) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto good = frac::mesh::make_random_lattice(rect(6, 4, 0.06, 0.04, 1.0, 2));
  ASSERT_TRUE(frac::mesh::check_cell_mesh(good).ok());
  // Each value a comparison could let through: a NaN fails no "greater than" test.
  auto m = good;
  m.area[5] = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: cell 5: area is not finite");
  m = good;
  m.second_moment[2] = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: cell 2: second_moment is not finite");
  m = good;
  m.centroid[3].y() = inf;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: cell 3: centroid is not finite");
  m = good;
  m.vertex[static_cast<std::size_t>(m.vertex_offset[1]) + 2].x() = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: cell 1: vertex 2 is not finite");
  m = good;
  m.beam_section[4] = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: beam 4: section is not finite");
  m = good;
  m.spacing = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: attribute spacing is not finite");
  m = good;
  m.bounds[1] = -inf;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "finite: attribute bounds is not finite");
  // A NaN and a real fault: the NaN alone (the rest would be noise).
  m = good;
  m.area[5] = nan;
  std::reverse(m.vertex.begin() + m.vertex_offset[2], m.vertex.begin() + m.vertex_offset[3]);
  EXPECT_EQ(frac::mesh::check_cell_mesh(m).failures.size(), 1u);
}

TEST(MeshCheck, NamesEachCellAndBeamFault) {
  const auto good = frac::mesh::make_random_lattice(rect(6, 4, 0.06, 0.04, 1.0, 2));
  auto m = good;
  m.area[6] = -m.area[6];
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)).rfind("area: cell 6: area -", 0), 0u)
      << first_failure(frac::mesh::check_cell_mesh(m));
  m = good;
  m.beam[4][1] = m.beam[4][0];
  const std::string self = "beam order: beam 4 (" + std::to_string(m.beam[4][0]) + ", " + std::to_string(m.beam[4][0]) +
                           ") joins a cell to itself";
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), self);
  m = good;
  m.beam_length[3] = 0;
  EXPECT_NE(first_failure(frac::mesh::check_cell_mesh(m)).find("beam 3 ("), std::string::npos);
  EXPECT_NE(first_failure(frac::mesh::check_cell_mesh(m)).find("0 m is not positive"), std::string::npos);
  // The spacing sets the tolerances: one far from the cells' size would pass anything.
  m = good;
  m.spacing = 1e6;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)).rfind("spacing: 1000000 m, far from", 0), 0u);
  m = good;
  m.spacing = -0.01;
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)), "spacing: -0.01 m is negative");
  // The box the loadings place their layers and sources in must hold the centroids.
  m = good;
  m.bounds = {0.0, 0.0, 0.03, 0.04};
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)).rfind("bounds: cell ", 0), 0u);
  m = good;
  m.bounds = {0.0, 0.05, 0.06, 0.04};
  EXPECT_EQ(first_failure(frac::mesh::check_cell_mesh(m)).rfind("bounds: box", 0), 0u);
}

TEST(MeshCheck, SurvivesAnyOffsetsAndCounts) {
  // Offsets of any value, counts of any size: no overflow, no index out of range, a failure each.
  const auto good = frac::mesh::make_random_lattice(rect(3, 3, 0.03, 0.03, 1.0, 2));
  for (const std::int64_t bad : {std::numeric_limits<std::int64_t>::min(), std::int64_t{-1}, std::int64_t{1},
                                 std::numeric_limits<std::int64_t>::max()}) {
    for (const std::size_t k : {std::size_t{1}, std::size_t{4}, good.vertex_offset.size() - 1}) {
      auto m = good;
      m.vertex_offset[k] = bad;
      const auto r = frac::mesh::check_cell_mesh(m);
      ASSERT_FALSE(r.ok()) << bad << " at " << k;
      EXPECT_EQ(r.failures[0].rfind("arrays: ", 0), 0u) << r.failures[0];
    }
  }
  TriangularLatticeOptions o;
  o.nx = 5, o.ny = 4, o.spacing = 1e-3;
  const auto nodes = frac::mesh::make_triangular_lattice(o);
  auto n = nodes;
  n.nx = std::int64_t{1} << 62, n.ny = 4;  // nx * ny wraps to 0 in 64 bits
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(n)), "nodes: 20 positions but nx * ny = 4611686018427387904 * 4");
  n = nodes;
  n.nx = -5;
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(n)).rfind("nodes: nx = -5", 0), 0u);
}

TEST(MeshCheck, NodeMeshFaultsNamedFiniteFirst) {
  TriangularLatticeOptions o;
  o.nx = 6, o.ny = 5, o.spacing = 1e-3;
  const auto good = frac::mesh::make_triangular_lattice(o);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto m = good;
  m.position[7].x() = nan;  // (the lattice builder would have called a bond of node 7 a duplicate)
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(m)), "finite: node 7: position is not finite");
  m = good;
  m.bond_length[2] = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(m)), "finite: bond 2: length is not finite");
  m = good;
  m.spacing = nan;
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(m)), "finite: attribute spacing is not finite");
  m = good;  // two nodes on one point, their bond of length 0: passes the distance test, not this one
  m.spacing = 0;
  m.position[1] = m.position[0];
  m.bond_length[0] = 0;
  EXPECT_NE(first_failure(frac::mesh::check_node_mesh(m)).find("0 m is not positive"), std::string::npos)
      << first_failure(frac::mesh::check_node_mesh(m));
  m = good;
  m.bond[3][1] = m.bond[3][0];
  EXPECT_NE(first_failure(frac::mesh::check_node_mesh(m)).find("joins a node to itself"), std::string::npos);
  m = good;
  m.rows_along = "z";
  EXPECT_EQ(first_failure(frac::mesh::check_node_mesh(m)), "rows_along: 'z': expected x or y");
}

// ---------------------------------------------------------------------------------------------
// Triangular lattice

TEST(Triangular, BondsAndDegreesBothOrientations) {
  for (const std::string along : {"x", "y"}) {
    TriangularLatticeOptions o;
    o.nx = 13;
    o.ny = 8;
    o.spacing = 2e-3;
    o.rows_along = along;
    const auto m = frac::mesh::make_triangular_lattice(o);
    ASSERT_EQ(m.nodes(), 13u * 8u);
    // Rows along x: (nx-1) ny in-row bonds + (ny-1)(2nx-1) between rows; rows along y:
    // nx (ny-1) in-column bonds + (nx-1)(2ny-1) between columns. Both are 3 nx ny - 2 nx - 2 ny + 1.
    EXPECT_EQ(m.bonds(), static_cast<std::size_t>(3 * 13 * 8 - 2 * 13 - 2 * 8 + 1)) << along;
    for (std::size_t e = 0; e < m.bonds(); ++e) {
      EXPECT_LT(m.bond[e][0], m.bond[e][1]);
      if (e > 0) {
        EXPECT_LT(m.bond[e - 1], m.bond[e]);
      }
      const double d =
          (m.position[static_cast<std::size_t>(m.bond[e][1])] - m.position[static_cast<std::size_t>(m.bond[e][0])])
              .norm();
      // Positions are products of small integers and Delta (sqrt(3)/2): round-off ~1e-16 relative.
      EXPECT_NEAR(d, o.spacing, 1e-12 * o.spacing);
      EXPECT_EQ(m.bond_length[e], o.spacing);
      EXPECT_EQ(m.intact[e], 1);
    }
    // Interior nodes have 6 bonds, and no pair of nodes closer than Delta is left unbonded.
    std::vector<int> deg(m.nodes(), 0);
    for (const auto& b : m.bond) {
      ++deg[static_cast<std::size_t>(b[0])];
      ++deg[static_cast<std::size_t>(b[1])];
    }
    for (std::int64_t j = 1; j + 1 < o.ny; ++j) {
      for (std::int64_t i = 1; i + 1 < o.nx; ++i) EXPECT_EQ(deg[static_cast<std::size_t>(j * o.nx + i)], 6);
    }
    std::size_t close_pairs = 0;
    for (std::size_t a = 0; a < m.nodes(); ++a) {
      for (std::size_t b = a + 1; b < m.nodes(); ++b) {
        if ((m.position[a] - m.position[b]).norm() < o.spacing * (1 + 1e-9)) ++close_pairs;
      }
    }
    EXPECT_EQ(close_pairs, m.bonds());
    // Layout: node (i, j) position.
    const double h = o.spacing * std::sqrt(3.0) / 2.0;
    const Vec2 p = m.position[static_cast<std::size_t>(3 * o.nx + 2)];  // i = 2, j = 3
    if (along == "x") {
      EXPECT_DOUBLE_EQ(p.x(), 2.5 * o.spacing);
      EXPECT_DOUBLE_EQ(p.y(), 3 * h);
    } else {
      EXPECT_DOUBLE_EQ(p.x(), 2 * h);
      EXPECT_DOUBLE_EQ(p.y(), 3 * o.spacing);
    }
    const auto report = frac::mesh::check_node_mesh(m);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.neighbour_count.at(6), (o.nx - 2) * (o.ny - 2));
  }
}

TEST(Triangular, NotchCutsTheExpectedBonds) {
  const double d = 1e-3, h = d * std::sqrt(3.0) / 2.0;
  for (const std::string along : {"x", "y"}) {
    for (const std::int64_t ny : {10, 11}) {
      TriangularLatticeOptions o;
      o.nx = 40;
      o.ny = ny;
      o.spacing = d;
      o.rows_along = along;
      o.notch = 10 * d;
      const auto m = frac::mesh::make_triangular_lattice(o);
      std::int64_t cut = 0;
      for (std::size_t e = 0; e < m.bonds(); ++e) {
        if (m.intact[e]) continue;
        ++cut;
        // Every cut bond crosses the notch line.
        const double ya = m.position[static_cast<std::size_t>(m.bond[e][0])].y() - m.notch_y;
        const double yb = m.position[static_cast<std::size_t>(m.bond[e][1])].y() - m.notch_y;
        EXPECT_LT(ya * yb, 0.0);
      }
      std::int64_t expected = 0;
      if (along == "x") {
        // Levels j h; the line lies between levels (ny-1)/2 and (ny-1)/2 + 1. The 2 nx - 1 bonds
        // between two rows cross it at x = (2k + 1) Delta / 4: those with x < 10 Delta are k < 20.
        EXPECT_NEAR(m.notch_y, (static_cast<double>((ny - 1) / 2) + 0.5) * h, 1e-15);
        expected = 20;
      } else {
        // Levels k Delta / 2 (2 ny of them); the line lies at (2 ny - 1) Delta / 4, the middle of the
        // sheet. It crosses one in-column bond per column (at x = i h) and one bond between each
        // pair of columns (at x = (i + 1/2) h): crossings at k h / 2 < 10 Delta, i.e. k <= 23.
        EXPECT_NEAR(m.notch_y, static_cast<double>(2 * ny - 1) * d / 4.0, 1e-15);
        expected = static_cast<std::int64_t>(std::floor(20.0 * d / h)) + 1;
        EXPECT_EQ(expected, 24);
      }
      EXPECT_EQ(cut, expected) << along << " ny " << ny;
      const auto report = frac::mesh::check_node_mesh(m);
      EXPECT_TRUE(report.ok());
      EXPECT_NE(report.summary.find("cut " + std::to_string(expected)), std::string::npos) << report.summary;
    }
  }
}

TEST(Triangular, BadOptionsNameTheOption) {
  using frac::mesh::make_triangular_lattice;
  TriangularLatticeOptions good;
  good.nx = 10;
  good.ny = 10;
  good.spacing = 1e-3;
  EXPECT_NO_THROW(make_triangular_lattice(good));
  auto o = good;
  o.nx = 1;
  expect_usage_error([&] { make_triangular_lattice(o); }, "--nodes");
  o = good;
  o.spacing = 0.0;
  expect_usage_error([&] { make_triangular_lattice(o); }, "--spacing");
  o = good;
  o.notch = -1e-3;
  expect_usage_error([&] { make_triangular_lattice(o); }, "--notch");
  o = good;
  o.notch = 1.0;  // wider than the lattice (9.5 mm)
  expect_usage_error([&] { make_triangular_lattice(o); }, "--notch");
  o = good;
  o.rows_along = "z";
  expect_usage_error([&] { make_triangular_lattice(o); }, "--rows-along");
}

// `m` with a copy of cell k as one more cell, stacked on it; without beams, so that every other invariant holds.
CellMesh with_stacked_copy(CellMesh m, std::size_t k) {
  const auto poly = m.polygon(k);
  m.vertex.insert(m.vertex.end(), poly.begin(), poly.end());
  m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
  m.centroid.push_back(m.centroid[k]), m.area.push_back(m.area[k]), m.second_moment.push_back(m.second_moment[k]);
  return m;
}

TEST(MeshCheck, CellsStackedOrShiftedOntoOthersOverlap) {
  const auto good = frac::mesh::make_random_lattice(rect(8, 4, 0.08, 0.04, 1.0, 5));
  const auto stacked = with_stacked_copy(good, 5);
  const auto r = frac::mesh::check_cell_mesh(stacked);
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_EQ(r.failures[0].rfind("overlap: cells 5 and 32 overlap by ", 0), 0u) << r.failures[0];
  EXPECT_NE(r.failures[0].find("m^2 (100% of the smaller), centroids 0 m apart"), std::string::npos) << r.failures[0];
  // Moved by a fifth of the spacing, the copy overlaps cell 5 and some of its neighbours, and nothing else does.
  auto shifted = stacked;
  shifted.centroid.back() += Vec2(0.002, 0.0);
  const auto s = frac::mesh::find_cell_overlaps(shifted, 1e-10, 0.01, 100);
  ASSERT_GE(s.found.size(), 2u);
  EXPECT_TRUE(s.complete);
  for (const auto& o : s.found) {
    EXPECT_EQ(o.b, 32u);
    EXPECT_GT(o.area, 0.0);
  }
  EXPECT_EQ(s.found[0].a, 5u);
}

TEST(MeshCheck, NoOverlapInTheLatticesOfAnyDisorder) {
  for (const double disorder : {0.0, 0.5, 1.0}) {
    const auto m = frac::mesh::make_random_lattice(rect(30, 20, 0.3, 0.2, disorder, 3));
    const auto s = frac::mesh::find_cell_overlaps(m, 1e-8 * m.spacing, m.spacing, 10);
    EXPECT_TRUE(s.found.empty() && s.complete) << "disorder " << disorder;
  }
  RandomLatticeOptions d;
  d.shape = "disc", d.diameter = 0.4, d.cells = 1100, d.disorder_region = "disc", d.seed = 7;
  const auto disc = frac::mesh::make_random_lattice(d);
  const auto s = frac::mesh::find_cell_overlaps(disc, 1e-8 * disc.spacing, disc.spacing, 10);
  EXPECT_TRUE(s.found.empty() && s.complete);
  EXPECT_LT(s.pairs, 64 * disc.cells());
}

// Unit squares (x, y) to (x + 1, y + 1) and one rectangle, for the wide-cell cases.
std::vector<std::vector<Vec2>> squares_and(int nx, int ny, const std::vector<std::vector<Vec2>>& more) {
  std::vector<std::vector<Vec2>> p;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) p.push_back({Vec2(x, y), Vec2(x + 1, y), Vec2(x + 1, y + 1), Vec2(x, y + 1)});
  p.insert(p.end(), more.begin(), more.end());
  return p;
}
std::vector<Vec2> box(double x0, double y0, double x1, double y1) {
  return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

TEST(CellOverlaps, AWideCellIsComparedWithEveryCellInItsReach) {
  // A 6 x 6 square over the middle of 20 x 20 unit squares: it covers 36 of them and touches 24 more.
  const auto m = frac::mesh::make_cell_mesh(squares_and(20, 20, {box(7, 7, 13, 13)}), {}, {}, 1.0);
  const auto s = frac::mesh::find_cell_overlaps(m, 1e-8, 1.0, 1000);
  ASSERT_EQ(s.found.size(), 36u);
  for (const auto& o : s.found) {
    EXPECT_EQ(o.b, 400u);
    EXPECT_NEAR(o.area, 1.0, 1e-12);
  }
  EXPECT_TRUE(s.complete);
}

TEST(CellOverlaps, CellsTooUnequalInSizeAreReportedNotCompared) {
  // 700 unit squares in a row under 300 strips as long as the row: no overlap, but 300 x 700 pairs within reach,
  // more than the linear budget.
  std::vector<std::vector<Vec2>> strips;
  for (int k = 0; k < 300; ++k) strips.push_back(box(0, 1 + 0.01 * k, 700, 1 + 0.01 * (k + 1)));
  const auto m = frac::mesh::make_cell_mesh(squares_and(700, 1, strips), {}, {}, 1.0);
  const auto s = frac::mesh::find_cell_overlaps(m, 1e-8, 1.0, 1000);
  EXPECT_TRUE(s.found.empty());
  EXPECT_FALSE(s.complete);
  EXPECT_EQ(s.widest, 700u);
  const std::string failure = first_failure(frac::mesh::check_cell_mesh(m));
  EXPECT_EQ(failure.rfind("overlap: not checked: cell 700 reaches so far beyond the others", 0), 0u) << failure;
}

TEST(CellOverlaps, CentroidsOfAnyFiniteValueAreSafe) {
  // Centroids 2e308 m apart (their distance overflows) and huge cells: no overflow into an index, an answer.
  for (const double far : {1e308, 1.7e308}) {
    auto m = frac::mesh::make_cell_mesh(squares_and(4, 1, {}), {}, {}, 1.0);
    m.centroid[0].x() = -far, m.centroid[3].x() = far;
    EXPECT_TRUE(frac::mesh::find_cell_overlaps(m, 1e-8, 1.0, 10).found.empty());
    for (auto& v : m.vertex) v *= 1e300;
    frac::mesh::find_cell_overlaps(m, 1e-8, 1.0, 10);
  }
}

// Not a test: time make_random_lattice (and the check) for 10^4, 10^5, 10^6 cells. Run with
//   unit_mesh --gtest_also_run_disabled_tests --gtest_filter='*RandomLatticeTiming*'
TEST(RandomLattice, DISABLED_RandomLatticeTiming) {
  for (const std::int64_t n : {100, 316, 1000}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto m = frac::mesh::make_random_lattice(rect(n, n, 1.0, 1.0, 1.0, 1));
    const auto t1 = std::chrono::steady_clock::now();
    const auto report = frac::mesh::check_cell_mesh(m);
    const auto t2 = std::chrono::steady_clock::now();
    frac::mesh::find_cell_overlaps(m, 1e-8 * m.spacing, m.spacing, 10);
    const auto t3 = std::chrono::steady_clock::now();
    std::cout << m.cells() << " cells, " << m.beams() << " beams: make "
              << std::chrono::duration<double>(t1 - t0).count() << " s, check "
              << std::chrono::duration<double>(t2 - t1).count() << " s (of which the overlap search "
              << std::chrono::duration<double>(t3 - t2).count() << " s), ok " << report.ok() << "\n";
  }
}

}  // namespace
