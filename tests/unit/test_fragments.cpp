// Fragments (analysis/fragments, analysis/fragments_io): exact clusters of hand-built states (chains, rings,
// an isolated cell, touching cells without beams), conservation of mass, momentum and kinetic energy,
// independence of the cell and beam numbering, the time-series counter, the log-binned mass
// histogram, and the run -> fragments file round trip with its refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <string>

#include "analysis/fragments.hpp"
#include "analysis/fragments_io.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "core/rng.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"
#include "io/run_io.hpp"
#include "mesh/random_lattice.hpp"
#include "mesh_test_support.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace frac;
using analysis::CellState;
using analysis::Fragments;
using frac::test::temp_dir;

namespace {

// Owned arrays behind a CellState.
struct State {
  std::vector<double> mass, inertia, position, velocity, angular_velocity;
  std::vector<std::int64_t> beam;
  std::vector<std::uint8_t> intact;
  CellState view() const { return {mass, inertia, position, velocity, angular_velocity, beam, intact}; }
  std::size_t cells() const { return mass.size(); }
  std::size_t beams() const { return intact.size(); }
  // Breaks the beam joining a and b (either order); fails the test when there is none.
  void cut(std::int64_t a, std::int64_t b) {
    for (std::size_t k = 0; k < beams(); ++k)
      if ((beam[2 * k] == a && beam[2 * k + 1] == b) || (beam[2 * k] == b && beam[2 * k + 1] == a)) {
        intact[k] = 0;
        return;
      }
    ADD_FAILURE() << "no beam " << a << "-" << b;
  }
};

// n unit-mass cells at rest, at x = 0, 1, 2, ..., with the given beams, all intact.
State cells_with_beams(std::size_t n, const std::vector<std::array<std::int64_t, 2>>& beams) {
  State s;
  s.mass.assign(n, 1.0);
  s.inertia.assign(n, 1.0 / 6.0);
  s.position.assign(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) s.position[2 * i] = static_cast<double>(i);
  s.velocity.assign(2 * n, 0.0);
  s.angular_velocity.assign(n, 0.0);
  for (const auto& b : beams) s.beam.insert(s.beam.end(), b.begin(), b.end());
  s.intact.assign(beams.size(), 1);
  return s;
}

mesh::CellMesh square_grid(int nx, int ny) { return mesh::make_square_grid(nx, ny); }

State state_of(const mesh::CellMesh& m) {
  State s;
  const std::size_t n = m.cells();
  s.mass = m.area;
  s.inertia = m.second_moment;
  for (const auto& c : m.centroid) s.position.insert(s.position.end(), {c.x(), c.y()});
  s.velocity.assign(2 * n, 0.0);
  s.angular_velocity.assign(n, 0.0);
  for (const auto& b : m.beam) s.beam.insert(s.beam.end(), b.begin(), b.end());
  s.intact.assign(m.beams(), 1);
  return s;
}

// A Voronoi block with random masses (so no two fragments tie), motions, and half its beams broken.
State random_state(std::uint64_t seed, double broken = 0.5) {
  mesh::RandomLatticeOptions opt;
  opt.width = 0.3, opt.height = 0.2, opt.nx = 30, opt.ny = 20, opt.seed = seed;
  State s = state_of(mesh::make_random_lattice(opt));
  Rng rng(seed + 100);
  for (auto& m : s.mass) m *= 25.0 * rng.uniform(0.5, 1.5);
  for (auto& i : s.inertia) i *= 25.0 * rng.uniform(0.5, 1.5);
  for (auto& x : s.position) x += rng.uniform(-0.01, 0.01) + 3.0;  // away from the origin
  for (auto& v : s.velocity) v = rng.uniform(-5.0, 5.0) + 2.0;     // a net drift
  for (auto& w : s.angular_velocity) w = rng.uniform(-50.0, 50.0);
  for (auto& f : s.intact) f = rng.uniform() < broken ? 0 : 1;
  return s;
}

double rel(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

// A run on a 4 x 3 grid of three frames at rest (frame k at step 10 k, t = 0.1 k s), frame k spoiled by `spoil`.
std::string write_grid_run(const fs::path& dir, const std::function<void(int, io::BodyFrame&)>& spoil) {
  const std::string path = (dir / "run.h5").string();
  const mesh::CellMesh m = square_grid(4, 3);
  const std::size_t n = m.cells(), b = m.beams();
  io::OutputFile out(path);
  io::write_header(out.root(), "run", start_run("t", "t"), out.uuid());
  io::RunWriter w(out.root(), m, std::vector<double>(n, 1.0), std::vector<double>(n, 0.2));
  for (int k = 0; k < 3; ++k) {
    io::BodyFrame f;
    for (const auto& c : m.centroid) f.position.insert(f.position.end(), {c.x(), c.y()});
    f.velocity.assign(2 * n, 0.0), f.angle.assign(n, 0.0), f.angular_velocity.assign(n, 0.0);
    f.intact.assign(b, 1), f.strain.assign(b, 0.0);
    f.step = 10 * k, f.time = 0.1 * k;
    spoil(k, f);
    w.write_frame(f);
  }
  w.finish();
  out.commit();
  return path;
}

// The message of the InputError `f` throws; "(no error)" if none.
std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Components by breadth-first search: an independent check of the union-find labels.
std::vector<std::int64_t> bfs_components(const State& s) {
  const std::size_t n = s.cells();
  std::vector<std::vector<std::int64_t>> adj(n);
  for (std::size_t k = 0; k < s.beams(); ++k)
    if (s.intact[k]) {
      adj[s.beam[2 * k]].push_back(s.beam[2 * k + 1]);
      adj[s.beam[2 * k + 1]].push_back(s.beam[2 * k]);
    }
  std::vector<std::int64_t> comp(n, -1);
  std::int64_t next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (comp[i] >= 0) continue;
    std::queue<std::int64_t> q;
    q.push(static_cast<std::int64_t>(i));
    comp[i] = next;
    while (!q.empty()) {
      const auto a = q.front();
      q.pop();
      for (auto b : adj[a])
        if (comp[b] < 0) comp[b] = next, q.push(b);
    }
    ++next;
  }
  return comp;
}

// Same partition: a one-to-one map between the labels of a and b.
bool same_partition(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
  if (a.size() != b.size()) return false;
  std::vector<std::int64_t> ab(a.size() + 1, -1), ba(b.size() + 1, -1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (ab[a[i]] < 0) ab[a[i]] = b[i];
    if (ba[b[i]] < 0) ba[b[i]] = a[i];
    if (ab[a[i]] != b[i] || ba[b[i]] != a[i]) return false;
  }
  return true;
}

}  // namespace

TEST(UnionFind, JoinsAndCounts) {
  analysis::UnionFind uf(6);
  uf.unite(0, 1);
  uf.unite(2, 3);
  uf.unite(1, 3);
  EXPECT_EQ(uf.find(0), uf.find(2));
  EXPECT_NE(uf.find(0), uf.find(4));
  EXPECT_EQ(uf.set_size(uf.find(3)), 4);
  EXPECT_EQ(uf.set_size(uf.find(5)), 1);
  uf.reset(3);
  EXPECT_EQ(uf.size(), 3u);
  EXPECT_NE(uf.find(0), uf.find(1));
}

TEST(Fragments, ChainCutOnce) {
  // 0-1-2-3-4, beam 2-3 broken: {0,1,2} (mass 3) then {3,4} (mass 2).
  State s = cells_with_beams(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  s.cut(2, 3);
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 2u);
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 0, 0, 1, 1}));
  EXPECT_EQ(f.mass, (std::vector<double>{3.0, 2.0}));
  EXPECT_EQ(f.cell_count, (std::vector<std::int64_t>{3, 2}));
  EXPECT_EQ(f.first_cell, (std::vector<std::int64_t>{0, 3}));
  EXPECT_DOUBLE_EQ(f.center_of_mass[0], 1.0);
  EXPECT_DOUBLE_EQ(f.center_of_mass[2], 3.5);
  EXPECT_EQ(f.total_mass, 5.0);
  EXPECT_EQ(f.singles(), 0u);
}

TEST(Fragments, ChainIntactIsOneFragmentAndAllBrokenIsSingles) {
  State s = cells_with_beams(5, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  EXPECT_EQ(analysis::find_fragments(s.view()).fragments(), 1u);
  std::fill(s.intact.begin(), s.intact.end(), 0);
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 5u);
  // Equal masses: ties go by the smallest cell index.
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(f.singles(), 5u);
  EXPECT_EQ(f.count_at_least(2), 0u);
}

TEST(Fragments, RingNeedsTwoCuts) {
  // Ring of 8 cells with masses 1..8; one cut keeps it whole, two cuts make two arcs.
  std::vector<std::array<std::int64_t, 2>> ring;
  for (std::int64_t k = 0; k < 8; ++k) ring.push_back({k, (k + 1) % 8});
  State s = cells_with_beams(8, ring);
  for (std::size_t k = 0; k < 8; ++k) s.mass[k] = 1.0 + static_cast<double>(k);
  s.cut(0, 1);
  EXPECT_EQ(analysis::find_fragments(s.view()).fragments(), 1u);
  s.cut(4, 5);
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 2u);
  // {5,6,7,0}: 6+7+8+1 = 22 comes before {1,2,3,4}: 2+3+4+5 = 14.
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 1, 1, 1, 1, 0, 0, 0}));
  EXPECT_EQ(f.mass, (std::vector<double>{22.0, 14.0}));
  EXPECT_EQ(f.first_cell, (std::vector<std::int64_t>{0, 1}));
}

TEST(Fragments, CellWithAllBeamsBroken) {
  // 3x3 squares; the centre cell (4) loses its four beams: a ring of 8 and a single cell.
  State s = state_of(square_grid(3, 3));
  for (std::int64_t other : {1, 3, 5, 7}) s.cut(4, other);
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 2u);
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 0, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(f.cell_count, (std::vector<std::int64_t>{8, 1}));
  EXPECT_EQ(f.mass, (std::vector<double>{8.0, 1.0}));
  EXPECT_EQ(f.singles(), 1u);
  EXPECT_EQ(f.count_at_least(2), 1u);
  EXPECT_EQ(f.masses_at_least(2), (std::vector<double>{8.0}));
  EXPECT_EQ(f.masses_at_least(1), (std::vector<double>{8.0, 1.0}));
  // The ring's centre of mass is the grid's centre, where the single cell is.
  EXPECT_DOUBLE_EQ(f.center_of_mass[0], 1.5);
  EXPECT_DOUBLE_EQ(f.center_of_mass[1], 1.5);
  EXPECT_DOUBLE_EQ(f.center_of_mass[2], 1.5);
  EXPECT_DOUBLE_EQ(f.center_of_mass[3], 1.5);
}

TEST(Fragments, TouchingCellsWithoutBeamsStayApart) {
  // 2x2 squares all touching; beams only 0-1 and 2-3 (the rows): two fragments, whatever the contacts.
  mesh::CellMesh m = square_grid(2, 2);
  m.beam = {{0, 1}, {2, 3}};
  State s = state_of(m);
  // Press the rows into each other: positions overlapping do not join them.
  s.position[5] = s.position[1] + 0.9;
  s.position[7] = s.position[3] + 0.9;
  Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 2u);
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 0, 1, 1}));  // equal masses: row with cell 0 first
  // Two equal fragments numbered the other way round keep the tie rule: the one holding cell 0 is 0.
  State t = cells_with_beams(4, {{2, 3}, {0, 1}});
  f = analysis::find_fragments(t.view());
  EXPECT_EQ(f.cell_fragment, (std::vector<std::int64_t>{0, 0, 1, 1}));
}

TEST(Fragments, LabelsAreTheComponentsOfTheIntactBeams) {
  for (double broken : {0.0, 0.3, 0.5, 0.7, 1.0}) {
    const State s = random_state(11, broken);
    const Fragments f = analysis::find_fragments(s.view());
    EXPECT_TRUE(same_partition(f.cell_fragment, bfs_components(s))) << "broken " << broken;
    std::vector<std::int64_t> count(f.fragments(), 0);
    for (auto id : f.cell_fragment) ++count[id];
    EXPECT_EQ(count, f.cell_count);
    EXPECT_TRUE(std::is_sorted(f.mass.begin(), f.mass.end(), std::greater<>()));
    for (std::size_t j = 0; j < f.fragments(); ++j)
      EXPECT_EQ(f.cell_fragment[f.first_cell[j]], static_cast<std::int64_t>(j));
  }
}

TEST(Fragments, ConservesMassMomentumAndKineticEnergy) {
  for (double broken : {0.0, 0.4, 0.6, 1.0}) {
    const State s = random_state(3, broken);
    const Fragments f = analysis::find_fragments(s.view());
    double mass = 0, mx = 0, my = 0, px = 0, py = 0, pabs = 0, ke = 0;
    for (std::size_t i = 0; i < s.cells(); ++i) {
      const double m = s.mass[i], vx = s.velocity[2 * i], vy = s.velocity[2 * i + 1], w = s.angular_velocity[i];
      mass += m;
      mx += m * s.position[2 * i];
      my += m * s.position[2 * i + 1];
      px += m * vx;
      py += m * vy;
      pabs += m * std::hypot(vx, vy);
      ke += 0.5 * (m * (vx * vx + vy * vy) + s.inertia[i] * w * w);
    }
    double fmass = 0, fmx = 0, fmy = 0, fpx = 0, fpy = 0, fke = 0;
    std::int64_t cells = 0;
    for (std::size_t j = 0; j < f.fragments(); ++j) {
      fmass += f.mass[j];
      fmx += f.mass[j] * f.center_of_mass[2 * j];
      fmy += f.mass[j] * f.center_of_mass[2 * j + 1];
      fpx += f.mass[j] * f.velocity[2 * j];
      fpy += f.mass[j] * f.velocity[2 * j + 1];
      fke += f.kinetic_energy_translational[j] + f.kinetic_energy_rotational[j];
      cells += f.cell_count[j];
      EXPECT_GE(f.kinetic_energy_rotational[j], 0.0);
    }
    EXPECT_EQ(cells, static_cast<std::int64_t>(s.cells()));
    EXPECT_LE(rel(fmass, mass), 1e-12) << "broken " << broken;
    EXPECT_LE(rel(f.total_mass, mass), 1e-12);
    EXPECT_LE(rel(fmx, mx), 1e-12);
    EXPECT_LE(rel(fmy, my), 1e-12);
    // Momentum: relative to the sum of |p| of the cells (the total itself may be small).
    EXPECT_LE(std::abs(fpx - px), 1e-12 * pabs);
    EXPECT_LE(std::abs(fpy - py), 1e-12 * pabs);
    EXPECT_LE(rel(fke, ke), 1e-12) << "broken " << broken;
  }
}

TEST(Fragments, SingleCellKeepsItsOwnMotion) {
  // A single cell: its velocity is the fragment's, its spin is all the rotational energy.
  State s = cells_with_beams(1, {});
  s.mass = {2.0};
  s.inertia = {0.5};
  s.velocity = {3.0, -4.0};
  s.angular_velocity = {6.0};
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 1u);
  EXPECT_EQ(f.velocity, (std::vector<double>{3.0, -4.0}));
  EXPECT_DOUBLE_EQ(f.kinetic_energy_translational[0], 25.0);
  EXPECT_DOUBLE_EQ(f.kinetic_energy_rotational[0], 9.0);
}

TEST(Fragments, RigidMotionSplitsIntoTranslationAndRotation) {
  // A 4x3 block translating at V and turning rigidly at Omega about its centre of mass:
  // T = M |V|^2 / 2 and R = Omega^2 (sum m r^2 + sum I) / 2.
  State s = state_of(square_grid(4, 3));
  Rng rng(5);
  for (auto& m : s.mass) m = rng.uniform(0.5, 2.0);
  for (auto& i : s.inertia) i = rng.uniform(0.1, 0.3);
  double mass = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < s.cells(); ++i) {
    mass += s.mass[i];
    cx += s.mass[i] * s.position[2 * i];
    cy += s.mass[i] * s.position[2 * i + 1];
  }
  cx /= mass, cy /= mass;
  const double vx = 1.5, vy = -0.5, omega = 2.0;
  double spin = 0;
  for (std::size_t i = 0; i < s.cells(); ++i) {
    const double rx = s.position[2 * i] - cx, ry = s.position[2 * i + 1] - cy;
    s.velocity[2 * i] = vx - omega * ry;
    s.velocity[2 * i + 1] = vy + omega * rx;
    s.angular_velocity[i] = omega;
    spin += s.mass[i] * (rx * rx + ry * ry) + s.inertia[i];
  }
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.fragments(), 1u);
  EXPECT_LE(rel(f.center_of_mass[0], cx), 1e-14);
  EXPECT_LE(rel(f.center_of_mass[1], cy), 1e-14);
  EXPECT_LE(rel(f.velocity[0], vx), 1e-12);
  EXPECT_LE(rel(f.velocity[1], vy), 1e-12);
  EXPECT_LE(rel(f.kinetic_energy_translational[0], 0.5 * mass * (vx * vx + vy * vy)), 1e-12);
  EXPECT_LE(rel(f.kinetic_energy_rotational[0], 0.5 * omega * omega * spin), 1e-12);
}

TEST(Fragments, IndependentOfCellAndBeamNumbering) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const State s = random_state(seed, 0.55);
    const std::size_t n = s.cells(), b = s.beams();
    // New index p[i] of old cell i; beams shuffled, and their two ends swapped at random.
    Rng rng(seed * 7 + 1);
    std::vector<std::int64_t> p(n), q(b);
    std::iota(p.begin(), p.end(), 0);
    std::iota(q.begin(), q.end(), 0);
    for (std::size_t k = n; k > 1; --k) std::swap(p[k - 1], p[static_cast<std::size_t>(rng.next() % k)]);
    for (std::size_t k = b; k > 1; --k) std::swap(q[k - 1], q[static_cast<std::size_t>(rng.next() % k)]);
    State t = s;
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(p[i]);
      t.mass[j] = s.mass[i];
      t.inertia[j] = s.inertia[i];
      t.angular_velocity[j] = s.angular_velocity[i];
      for (int c = 0; c < 2; ++c) {
        t.position[2 * j + c] = s.position[2 * i + c];
        t.velocity[2 * j + c] = s.velocity[2 * i + c];
      }
    }
    for (std::size_t k = 0; k < b; ++k) {
      const auto nk = static_cast<std::size_t>(q[k]);
      const bool swap = rng.uniform() < 0.5;
      t.beam[2 * nk] = p[s.beam[2 * k + (swap ? 1 : 0)]];
      t.beam[2 * nk + 1] = p[s.beam[2 * k + (swap ? 0 : 1)]];
      t.intact[nk] = s.intact[k];
    }
    const Fragments a = analysis::find_fragments(s.view());
    const Fragments c = analysis::find_fragments(t.view());
    ASSERT_EQ(a.fragments(), c.fragments());
    ASSERT_GT(a.fragments(), 10u);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(c.cell_fragment[p[i]], a.cell_fragment[i]) << "cell " << i;
    EXPECT_EQ(a.cell_count, c.cell_count);
    for (std::size_t j = 0; j < a.fragments(); ++j) {
      EXPECT_LE(rel(a.mass[j], c.mass[j]), 1e-15);
      for (int k = 0; k < 2; ++k) {
        EXPECT_LE(rel(a.center_of_mass[2 * j + k], c.center_of_mass[2 * j + k]), 1e-12);
        EXPECT_LE(std::abs(a.velocity[2 * j + k] - c.velocity[2 * j + k]), 1e-12 * 10.0);
      }
      EXPECT_LE(rel(a.kinetic_energy_translational[j], c.kinetic_energy_translational[j]), 1e-12);
      EXPECT_LE(rel(a.kinetic_energy_rotational[j], c.kinetic_energy_rotational[j]), 1e-12);
    }
  }
}

TEST(Fragments, CounterAgreesWithFullAnalysisAndReusesItsWorkspace) {
  analysis::FragmentCounter counter;
  for (double broken : {0.0, 0.5, 0.8, 1.0}) {
    const State s = random_state(9, broken);
    const Fragments f = analysis::find_fragments(s.view());
    for (std::int64_t min_cells : {1, 2, 3}) {
      const auto c = counter(s.mass, s.beam, s.intact, min_cells);
      EXPECT_EQ(c.count, static_cast<std::int64_t>(f.count_at_least(min_cells)));
      EXPECT_LE(rel(c.largest_mass, f.mass[0]), 1e-12);
    }
  }
}

TEST(Fragments, RefusesInconsistentStates) {
  const auto refuses = [](State s, const std::string& needle) {
    try {
      analysis::find_fragments(s.view());
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted a bad state (" << needle << ")";
  };
  const State good = cells_with_beams(3, {{0, 1}, {1, 2}});
  State s = good;
  s.inertia.pop_back();
  refuses(s, "inertia");
  s = good;
  s.position.pop_back();
  refuses(s, "position");
  s = good;
  s.intact.pop_back();
  refuses(s, "intact");
  s = good;
  s.beam[3] = 3;
  refuses(s, "beam 1 joins cell 3");
  s = good;
  s.beam[0] = -1;
  refuses(s, "beam 0 joins cell -1");
  s = good;
  s.mass[1] = -1.0;
  refuses(s, "mass");
  s = good;
  s.mass[2] = 0.0;
  refuses(s, "mass: value 0.000000 at index 2");
  s = good;
  s.velocity[2] = std::nan("");
  refuses(s, "velocity");
}

TEST(MassHistogram, BinsTheFragmentsOfAtLeastMinCells) {
  // 3x3 squares of masses 1..9 g... in kg: the centre cut off, then a corner too.
  State s = state_of(square_grid(3, 3));
  for (std::size_t i = 0; i < 9; ++i) s.mass[i] = 1.0 + static_cast<double>(i);
  for (std::int64_t other : {1, 3, 5, 7}) s.cut(4, other);
  s.cut(0, 1);
  s.cut(0, 3);
  const Fragments f = analysis::find_fragments(s.view());
  ASSERT_EQ(f.mass, (std::vector<double>{39.0, 5.0, 1.0}));  // ring without 0, centre (5), corner (1)
  // All three, one bin a decade of the mean cell mass u = 45/9 = 5: the edges 0.1u, u and 10u, the last two
  // moved halfway between whole numbers of cells (0.5u, 9.5u): [0.5, 2.5) holds 1, [2.5, 47.5) holds 5 and 39.
  auto h = analysis::mass_histogram(f, 1, 1.0);
  ASSERT_EQ(h.count, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(h.edges, (std::vector<double>{0.5, 2.5, 47.5}));
  EXPECT_DOUBLE_EQ(h.density[0], 1.0 / (3.0 * 2.0));
  EXPECT_DOUBLE_EQ(h.density[1], 2.0 / (3.0 * 45.0));
  // Without single cells only the ring is left; with min_cells 9 nothing is: no bins.
  h = analysis::mass_histogram(f, 2, 5.0);
  EXPECT_EQ(h.n_total, 1);
  ASSERT_EQ(h.count, (std::vector<std::int64_t>{1}));
  EXPECT_LE(h.edges[0], 39.0);
  EXPECT_GT(h.edges[1], 39.0);
  h = analysis::mass_histogram(f, 9, 5.0);
  EXPECT_TRUE(h.count.empty());
  EXPECT_TRUE(h.edges.empty());
  EXPECT_THROW(analysis::mass_histogram(f, 1, 0.0), UsageError);
  // On a broken Voronoi block: counts add up to the fragments selected, density integrates to 1.
  const Fragments g = analysis::find_fragments(random_state(4, 0.6).view());
  for (std::int64_t min_cells : {1, 2, 5}) {
    h = analysis::mass_histogram(g, min_cells, 5.0);
    std::int64_t total = 0;
    double integral = 0;
    for (std::size_t k = 0; k < h.size(); ++k) {
      total += h.count[k];
      integral += h.density[k] * (h.edges[k + 1] - h.edges[k]);
    }
    EXPECT_EQ(total, static_cast<std::int64_t>(g.count_at_least(min_cells)));
    EXPECT_NEAR(integral, 1.0, 1e-12);
  }
}

TEST(FragmentsIo, RunToFragmentsFileRoundTrip) {
  const auto dir = temp_dir("roundtrip");
  const auto run_path = (dir / "run.h5").string(), out_path = (dir / "fragments.h5").string();
  const mesh::CellMesh m = square_grid(4, 3);
  const std::size_t n = m.cells(), b = m.beams();
  std::vector<double> mass(n), inertia(n);
  for (std::size_t i = 0; i < n; ++i) mass[i] = 1.0 + 0.1 * static_cast<double>(i), inertia[i] = 0.2;
  {
    io::OutputFile out(run_path);
    ToolRun run = start_run("test-run", "test-run");
    io::write_header(out.root(), "run", run, out.uuid());
    io::RunWriter w(out.root(), m, mass, inertia);
    io::BodyFrame f;
    for (const auto& c : m.centroid) f.position.insert(f.position.end(), {c.x(), c.y()});
    f.velocity.assign(2 * n, 0.5);
    f.angle.assign(n, 0.0);
    f.angular_velocity.assign(n, 1.0);
    f.intact.assign(b, 1);
    f.strain.assign(b, 0.0);
    w.write_frame(f);
    // Frame 1: the last column (cells 3, 7, 11) cut off.
    f.step = 10, f.time = 0.5;
    for (std::size_t k = 0; k < b; ++k)
      if (m.beam[k][1] % 4 == 3 && m.beam[k][0] % 4 == 2) f.intact[k] = 0;
    f.velocity[2 * 7] = 2.0;
    w.write_frame(f);
    w.finish();
    out.commit();
  }
  const io::Group root = io::open_input(run_path);
  const io::RunInfo info = analysis::read_dem_run_info(root);
  ASSERT_EQ(info.step.size(), 2u);
  const analysis::FragmentInput in = analysis::read_fragment_input(root, info, 1);
  EXPECT_EQ(in.step, 10);
  EXPECT_EQ(in.time, 0.5);
  EXPECT_EQ(in.mass, mass);
  EXPECT_EQ(in.velocity[14], 2.0);
  EXPECT_EQ(std::count(in.intact.begin(), in.intact.end(), 0), 3);
  EXPECT_THROW(analysis::read_fragment_input(root, info, 2), InputError);

  analysis::FragmentRecord rec;
  rec.frame = in.frame, rec.step = in.step, rec.time = in.time, rec.min_cells = 2;
  rec.fragments = analysis::find_fragments(in.state());
  ASSERT_EQ(rec.fragments.fragments(), 2u);
  EXPECT_EQ(rec.fragments.cell_count, (std::vector<std::int64_t>{9, 3}));
  rec.histogram = analysis::mass_histogram(rec.fragments, 2, 5.0);
  rec.time_series = analysis::fragment_time_series(root, info, in.beam, 1);
  EXPECT_EQ(rec.time_series.step, (std::vector<std::int64_t>{0, 10}));
  EXPECT_EQ(rec.time_series.time, (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(rec.time_series.count, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(rec.time_series.largest_mass, (std::vector<double>{rec.fragments.total_mass, rec.fragments.mass[0]}));
  EXPECT_EQ(analysis::fragment_time_series(root, info, in.beam, 4).count, (std::vector<std::int64_t>{1, 1}));
  {
    io::OutputFile out(out_path);
    ToolRun run = start_run("test-count", "test-count");
    io::add_input(run, root);
    io::write_header(out.root(), "fragments", run, out.uuid());
    analysis::write_fragments(out.root(), rec);
    out.commit();
  }
  const io::Group back_root = io::open_input(out_path);
  EXPECT_EQ(io::check_header(back_root, {"fragments"}), "fragments");
  const analysis::FragmentRecord back = analysis::read_fragments(back_root);
  EXPECT_EQ(back.frame, 1);
  EXPECT_EQ(back.step, 10);
  EXPECT_EQ(back.time, 0.5);
  EXPECT_EQ(back.min_cells, 2);
  const auto& a = rec.fragments;
  const auto& c = back.fragments;
  EXPECT_EQ(c.cell_fragment, a.cell_fragment);
  EXPECT_EQ(c.mass, a.mass);
  EXPECT_EQ(c.cell_count, a.cell_count);
  EXPECT_EQ(c.first_cell, a.first_cell);
  EXPECT_EQ(c.center_of_mass, a.center_of_mass);
  EXPECT_EQ(c.velocity, a.velocity);
  EXPECT_EQ(c.kinetic_energy_translational, a.kinetic_energy_translational);
  EXPECT_EQ(c.kinetic_energy_rotational, a.kinetic_energy_rotational);
  EXPECT_EQ(c.total_mass, a.total_mass);
  EXPECT_EQ(back.histogram.count, rec.histogram.count);
  EXPECT_EQ(back.histogram.edges, rec.histogram.edges);
  EXPECT_EQ(back.histogram.density, rec.histogram.density);
  EXPECT_EQ(back.histogram.n_total, 2);
  EXPECT_EQ(back.histogram.bins_per_decade, 5.0);
  EXPECT_EQ(back.time_series.count, rec.time_series.count);
  EXPECT_EQ(back.time_series.largest_mass, rec.time_series.largest_mass);
  EXPECT_EQ(back_root.attr_string("unit", "fragments/kinetic_energy_rotational"), "J");
  EXPECT_EQ(back_root.attr_string("unit", "fragments/histogram/density"), "kg^-1");
  // The lineage: this file, then the run's history.
  const auto prov = io::read_provenance(back_root);
  ASSERT_EQ(prov.history.size(), 2u);
  EXPECT_EQ(prov.history[0].tool, "test-count");
  EXPECT_EQ(prov.history[1].tool, "test-run");
  fs::remove_all(dir);
}

TEST(FragmentsIo, IndependentOfNumberingThroughRunFiles) {
  // A Voronoi block and the same block renumbered (cells permuted, so the beams between them get new
  // numbers and order; every mesh keeps its beams sorted with cell_a < cell_b), each written as a run
  // file with the same broken beams and motions: the same fragments.
  const auto dir = temp_dir("renumbered");
  mesh::RandomLatticeOptions opt;
  opt.width = 0.2, opt.height = 0.2, opt.nx = 20, opt.ny = 20, opt.seed = 5;
  const mesh::CellMesh m = mesh::make_random_lattice(opt);
  const std::size_t n = m.cells(), b = m.beams();
  Rng rng(17);
  std::vector<std::int64_t> p(n), q(b);
  std::iota(p.begin(), p.end(), 0);
  for (std::size_t k = n; k > 1; --k) std::swap(p[k - 1], p[static_cast<std::size_t>(rng.next() % k)]);
  // Old beam k becomes beam q[k]: its rank among the renumbered pairs.
  const auto renumbered_pair = [&](std::size_t k) {
    const auto a = p[static_cast<std::size_t>(m.beam[k][0])], c = p[static_cast<std::size_t>(m.beam[k][1])];
    return std::array<std::int64_t, 2>{std::min(a, c), std::max(a, c)};
  };
  std::vector<std::size_t> order(b);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return renumbered_pair(x) < renumbered_pair(y); });
  for (std::size_t rank = 0; rank < b; ++rank) q[order[rank]] = static_cast<std::int64_t>(rank);
  mesh::CellMesh r = m;
  r.vertex.clear();
  r.vertex_offset = {0};
  std::vector<std::size_t> inverse(n);
  for (std::size_t i = 0; i < n; ++i) inverse[p[i]] = i;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = inverse[j];
    const auto poly = m.polygon(i);
    r.vertex.insert(r.vertex.end(), poly.begin(), poly.end());
    r.vertex_offset.push_back(static_cast<std::int64_t>(r.vertex.size()));
    r.centroid[j] = m.centroid[i], r.area[j] = m.area[i], r.second_moment[j] = m.second_moment[i];
  }
  for (std::size_t k = 0; k < b; ++k) {
    r.beam[q[k]] = renumbered_pair(k);
    r.beam_length[q[k]] = m.beam_length[k], r.beam_section[q[k]] = m.beam_section[k];
  }
  // Per old cell and old beam: mass, inertia, motion, intact flag.
  std::vector<double> mass(n), inertia(n), v(2 * n), w(n);
  std::vector<std::uint8_t> intact(b);
  for (std::size_t i = 0; i < n; ++i) {
    mass[i] = 25.0 * m.area[i] * rng.uniform(0.5, 1.5);
    inertia[i] = 25.0 * m.second_moment[i];
    v[2 * i] = rng.uniform(-1, 1), v[2 * i + 1] = rng.uniform(-1, 1), w[i] = rng.uniform(-10, 10);
  }
  for (auto& f : intact) f = rng.uniform() < 0.65 ? 0 : 1;
  const auto write = [&](const mesh::CellMesh& mm, bool renumbered, const std::string& path) {
    const auto cell = [&](std::size_t j) { return renumbered ? inverse[j] : j; };  // new -> old
    std::vector<double> ms(n), is(n);
    io::BodyFrame f;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = cell(j);
      ms[j] = mass[i], is[j] = inertia[i];
      f.position.insert(f.position.end(), {m.centroid[i].x(), m.centroid[i].y()});
      f.velocity.insert(f.velocity.end(), {v[2 * i], v[2 * i + 1]});
      f.angular_velocity.push_back(w[i]);
    }
    f.angle.assign(n, 0.0);
    f.intact.resize(b);
    for (std::size_t k = 0; k < b; ++k) f.intact[renumbered ? q[k] : k] = intact[k];
    f.strain.assign(b, 0.0);
    io::OutputFile out(path);
    io::write_header(out.root(), "run", start_run("t", "t"), out.uuid());
    io::RunWriter wr(out.root(), mm, ms, is);
    wr.write_frame(f);
    wr.finish();
    out.commit();
  };
  write(m, false, (dir / "a.h5").string());
  write(r, true, (dir / "b.h5").string());
  const auto count = [](const std::string& path) {
    const io::Group root = io::open_input(path);
    const auto info = analysis::read_dem_run_info(root);
    return analysis::find_fragments(analysis::read_fragment_input(root, info, 0).state());
  };
  const Fragments a = count((dir / "a.h5").string()), c = count((dir / "b.h5").string());
  ASSERT_EQ(a.fragments(), c.fragments());
  ASSERT_GT(a.fragments(), 10u);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(c.cell_fragment[p[i]], a.cell_fragment[i]) << "cell " << i;
  EXPECT_EQ(a.mass, c.mass);  // compensated sums: the same bits in any order
  EXPECT_EQ(a.cell_count, c.cell_count);
  for (std::size_t j = 0; j < a.fragments(); ++j) {
    EXPECT_LE(rel(a.kinetic_energy_translational[j], c.kinetic_energy_translational[j]), 1e-12);
    EXPECT_LE(rel(a.kinetic_energy_rotational[j], c.kinetic_energy_rotational[j]), 1e-12);
    for (int k = 0; k < 2; ++k) EXPECT_LE(rel(a.center_of_mass[2 * j + k], c.center_of_mass[2 * j + k]), 1e-12);
  }
  fs::remove_all(dir);
}

TEST(FragmentsIo, RefusesIntactFlagsOtherThanZeroOrOne) {
  const auto dir = temp_dir("intact");
  const std::string path = write_grid_run(dir, [](int k, io::BodyFrame& f) {
    if (k == 1) f.intact[2] = 7;
  });
  const io::Group root = io::open_input(path);
  const io::RunInfo info = analysis::read_dem_run_info(root);
  EXPECT_NO_THROW(analysis::read_fragment_input(root, info, 0));
  const std::string expected =
      path + ":/connectivity/beams/trajectory/intact/value: frame 1: beam 2: intact flag 7, expected 0 or 1";
  EXPECT_EQ(input_error_of([&] { analysis::read_fragment_input(root, info, 1); }), expected);
  const auto beam = analysis::read_beam_pairs(root, info.mass.size());
  EXPECT_EQ(input_error_of([&] { analysis::fragment_time_series(root, info, beam, 1); }), expected);
  fs::remove_all(dir);
}

TEST(FragmentsIo, RefusesFrameTimesAndStepsThatAreNegativeOrDecrease) {
  const auto dir = temp_dir("times");
  const auto refusal = [&](const std::function<void(int, io::BodyFrame&)>& spoil) {
    const std::string path = write_grid_run(dir, spoil);
    const std::string what = input_error_of([&] { analysis::read_dem_run_info(io::open_input(path)); });
    return what.rfind(path + ":/particles/cells/position/", 0) == 0 ? what.substr(path.size()) : what;
  };
  const char* times = " (frame times must be finite, >= 0 and non-decreasing)";
  EXPECT_EQ(refusal([](int k, io::BodyFrame& f) {
              if (k == 1) f.time = -1;
            }),
            ":/particles/cells/position/time: frame 1: t = -1 s after 0 s" + std::string(times));
  EXPECT_EQ(refusal([](int k, io::BodyFrame& f) {
              if (k == 0) f.time = std::numeric_limits<double>::quiet_NaN();
            }),
            ":/particles/cells/position/time: frame 0: t = nan s" + std::string(times));
  EXPECT_EQ(refusal([](int k, io::BodyFrame& f) {
              if (k == 2) f.time = 0.05;
            }),
            ":/particles/cells/position/time: frame 2: t = 0.05 s after 0.1 s" + std::string(times));
  EXPECT_EQ(refusal([](int k, io::BodyFrame& f) {
              if (k == 2) f.step = 5;
            }),
            ":/particles/cells/position/step: frame 2: step 5 after 10 (frame steps must be >= 0 and non-decreasing)");
  EXPECT_EQ(refusal([](int, io::BodyFrame&) {}), "(no error)");
  fs::remove_all(dir);
}

TEST(FragmentsIo, RefusesRubberRuns) {
  const auto dir = temp_dir("refuse");
  const auto path = (dir / "rubber.h5").string();
  {
    io::OutputFile out(path);
    io::write_header(out.root(), "run", start_run("t", "t"), out.uuid());
    const mesh::NodeMesh m = test::two_node_mesh();
    std::vector<double> mass{1.0, 1.0};
    io::RunWriter w(out.root(), m, mass);
    w.finish();
    out.commit();
  }
  try {
    analysis::read_dem_run_info(io::open_input(path));
    ADD_FAILURE() << "accepted a rubber run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model 'rubber'"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}
