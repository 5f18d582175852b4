// Contacts of the polygon DEM (lib/dem/contacts; physics/polygon-dem.md §3, validation E7-E8): the
// overlap force of two squares against a hand computation, damping and friction against the note's
// formulas, the neighbour search against brute force, and the conservation of momentum and angular
// momentum by all pair interactions on random overlapping configurations.
//
// Tolerance of the hand computations: 1e-12 relative. The library rotates the body-frame vertices by
// cos/sin of φ and clips them (Sutherland-Hodgman about a vertex of P_i), so every vertex, crossing
// and the overlap area carry a few ulps of the polygon size s; relative to the overlap (width δ ≥ 0.1 s)
// that is ~1e-14, and a translation by 0.3 m (ulp 5.6e-17 m on s = 1 cm) adds ~1e-13. 1e-12 leaves a
// factor of ten.
#include <gtest/gtest.h>
#include <array>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/rng.hpp"
#include "core/scene.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_laws.hpp"
#include "dem/contact_search.hpp"
#include "dem/model.hpp"
#include "dem/scene.hpp"
#include "dem/timestep.hpp"
#include "dynamics/integrator.hpp"
#include "geometry/overlap.hpp"
#include "geometry/polygon.hpp"
#include "mesh/random_lattice.hpp"
#include "test_support.hpp"

namespace {

using frac::dem::Bodies;
using frac::dem::ContactList;
using frac::dem::ContactSearch;
using frac::dem::Material;
using frac::dem::Model;
using frac::dem::Physics;
using frac::geometry::Vec2;
using frac::mesh::CellMesh;

constexpr double kPi = std::numbers::pi;
constexpr double kY = 1e9, kH = 0.01, kRho = 5000;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 perp(const Vec2& a) { return {-a.y(), a.x()}; }
Vec2 rot(const Vec2& a, double w) {
  return {std::cos(w) * a.x() - std::sin(w) * a.y(), std::sin(w) * a.x() + std::cos(w) * a.y()};
}

// A mesh of axis-aligned rectangles (w × h each) at the given reference centroids, no beams.
CellMesh rectangles(const std::vector<std::pair<double, double>>& sizes, const std::vector<Vec2>& centres, double g) {
  CellMesh m;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    const double w = sizes[k].first, h = sizes[k].second;
    for (const Vec2& v : {Vec2(-w / 2, -h / 2), Vec2(w / 2, -h / 2), Vec2(w / 2, h / 2), Vec2(-w / 2, h / 2)})
      m.vertex.push_back(v);
    m.vertex_offset.push_back(static_cast<std::int64_t>(m.vertex.size()));
    m.centroid.push_back(centres[k]);
    m.area.push_back(w * h);
    m.second_moment.push_back(w * h * (w * w + h * h) / 12);
  }
  m.shape = "rect";
  m.spacing = g;
  return m;
}

// State vector q = [x..., y..., φ...] of n bodies.
std::vector<double> state(const std::vector<Vec2>& c, const std::vector<double>& phi) {
  const std::size_t n = c.size();
  std::vector<double> q(3 * n);
  for (std::size_t k = 0; k < n; ++k) {
    q[k] = c[k].x();
    q[n + k] = c[k].y();
    q[2 * n + k] = phi[k];
  }
  return q;
}

// The note's pair law on two bodies, by hand: given the contact geometry (R, n, A) the forces and
// torques on i and j, with optional damping and friction.
struct PairForce {
  Vec2 fi;
  double ti, tj;
  double fn;  // normal force on i along n (elastic + damping)
};
struct Kin {
  Vec2 c, v;
  double w, m, diameter;
};
PairForce note_pair(const Kin& i, const Kin& j, const Vec2& R, const Vec2& n, double area, double gamma_n,
                    double gamma_t, double mu) {
  const double inv_lc = 0.5 * (1 / i.diameter + 1 / j.diameter);
  const Vec2 vrel = j.v + j.w * perp(R - j.c) - i.v - i.w * perp(R - i.c);
  const Vec2 t = perp(n);
  const double vn = vrel.dot(n), vt = vrel.dot(t);
  const double meff = i.m * j.m / (i.m + j.m);
  const double fn = -kY * area * kH * inv_lc + meff * gamma_n * vn;
  const double ft = (vt > 0 ? 1 : vt < 0 ? -1 : 0) * std::min(meff * gamma_t * std::abs(vt), mu * std::abs(fn));
  const Vec2 f = fn * n + ft * t;
  return {f, cross(R - i.c, f), cross(R - j.c, -f), fn};
}

struct Case {
  const char* name;
  std::vector<std::pair<double, double>> sizes;
  Vec2 cj;      // centroid of j (i at the origin), unrotated frame
  double area;  // hand: overlap area
  Vec2 R;       // hand: contact point
  Vec2 n;       // hand: unit normal from i to j
};

std::vector<Case> hand_cases() {
  const double s = 0.01, d = 0.15 * s, yoff = 0.3 * s;
  std::vector<Case> cs;
  {
    // Equal squares, j shifted right by s − δ and up by y_off. Overlap [s/2 − δ, s/2] × [y_off − s/2, s/2],
    // A = δ (s − y_off). i's right side crosses j's bottom at P1 = (s/2, y_off − s/2), j's left side crosses
    // i's top at P2 = (s/2 − δ, s/2): the contact line is the overlap's diagonal, R its midpoint, and n ⊥
    // P2 − P1 = (−δ, s − y_off), pointing from i to j.
    const Vec2 p1(s / 2, yoff - s / 2), p2(s / 2 - d, s / 2);
    const Vec2 nn = Vec2(s - yoff, d).normalized();
    cs.push_back(
        {"equal squares, corner overlap", {{s, s}, {s, s}}, Vec2(s - d, yoff), d * (s - yoff), 0.5 * (p1 + p2), nn});
  }
  {
    // A small square (side s2) pressed by δ into the right face of a big one (side s), off centre by y_off:
    // A = s2 δ, the contact line is the stretch of i's right side inside j, R = (s/2, y_off), n = +x.
    // The lever arm of R about c_i is y_off: τ_i = y_off·Y A h/L_c, τ_j = 0 (R on j's axis).
    // (y_off2 = 0.2 s keeps j's sides clear of i's top side: no collinear edges.)
    const double s2 = 0.4 * s, yoff2 = 0.2 * s;
    cs.push_back({"small square into a face, off centre",
                  {{s, s}, {s2, s2}},
                  Vec2(s / 2 + s2 / 2 - d, yoff2),
                  s2 * d,
                  Vec2(s / 2, yoff2),
                  Vec2(1, 0)});
  }
  {
    // Validation E7: equal squares face to face, pressed by δ: A = s δ, n along the centre line, R on it
    // (collinear top and bottom sides: the crossings are the midpoints of the shared runs), torque 0.
    cs.push_back({"equal squares face to face (E7)",
                  {{s, s}, {s, s}},
                  Vec2(s - d, 0),
                  s * d,
                  Vec2(s / 2 - d / 2, 0),
                  Vec2(1, 0)});
  }
  return cs;
}

// The contact laws' parameters (the material's: Y, h, γ_N, γ_T, μ).
struct ContactParameters {
  double grain_modulus, thickness, gamma_n, gamma_t, friction;
};

// The contact laws `names` with parameters p, and their powers summed over the list, on the threads of the test.
std::vector<double> law_powers(frac::dem::ContactList& list, const ContactParameters& p, const Bodies& bodies,
                               const std::vector<double>& q, const std::vector<double>& v,
                               const std::vector<std::string>& names) {
  Material m;
  m.grain_modulus = p.grain_modulus;
  m.thickness = p.thickness;
  m.gamma_n = p.gamma_n;
  m.gamma_t = p.gamma_t;
  m.friction = p.friction;
  const auto laws = frac::dem::make_contact_laws(frac::dem::contact_law_table(), names, m);
  return frac::dem::contact_forces(laws, list, bodies, q, v);
}

// Runs the library's search and the three contact laws on a two-body state.
struct LibResult {
  ContactList list;
  std::vector<double> f;
  double power[3];
};
LibResult library(const CellMesh& mesh, const Bodies& bodies, const std::vector<double>& q,
                  const std::vector<double>& v, const ContactParameters& p, bool damping, bool friction) {
  LibResult r;
  ContactSearch search(mesh, bodies);
  search.find(q, r.list);
  r.f.assign(q.size(), 0.0);
  std::vector<std::string> names{"contact"};
  if (damping) names.push_back("damping");
  if (friction) names.push_back("friction");
  const std::vector<double> power = law_powers(r.list, p, bodies, q, v, names);
  r.power[0] = power[0];
  r.power[1] = damping ? power[1] : 0.0;
  r.power[2] = friction ? power.back() : 0.0;
  frac::dem::add_contact_forces(r.list, bodies.n, q, r.f);
  return r;
}

TEST(DemContacts, OverlappingSquaresAgainstHandComputation) {
  Material mat;
  mat.density = kRho;
  mat.thickness = kH;
  mat.grain_modulus = kY;
  const ContactParameters p{kY, kH, 0.0, 0.0, 0.0};
  frac::Rng rng(17);
  double worst = 0;
  for (const Case& c : hand_cases()) {
    // The configuration as given, then turned rigidly by random angles and moved by up to 0.3 m.
    for (int t = 0; t < 12; ++t) {
      const double w = t == 0 ? 0.0 : (rng.uniform() - 0.5) * 4 * kPi;
      const Vec2 shift = t == 0 ? Vec2(0, 0) : Vec2(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
      const CellMesh mesh = rectangles(c.sizes, {Vec2(0, 0), c.cj}, 0.01);
      const Bodies bodies = frac::dem::make_bodies(mesh, mat);
      const Vec2 ci = shift, cj = shift + rot(c.cj, w);
      const auto q = state({ci, cj}, {w, w});
      const std::vector<double> v(6, 0.0);
      const LibResult r = library(mesh, bodies, q, v, p, false, false);
      ASSERT_EQ(r.list.size(), 1u) << c.name;
      const Vec2 R = shift + rot(c.R, w), n = rot(c.n, w);
      // Magnitude Y·A·h/L_c with 1/L_c = (1/r_i + 1/r_j)/2, r = 2·sqrt(A_poly/π).
      const double ri = 2 * std::sqrt(c.sizes[0].first * c.sizes[0].second / kPi);
      const double rj = 2 * std::sqrt(c.sizes[1].first * c.sizes[1].second / kPi);
      const double magnitude = kY * c.area * kH * 0.5 * (1 / ri + 1 / rj);
      const Vec2 fi = -magnitude * n;  // repulsion: i pushed away from j
      const double ti = cross(R - ci, fi), tj = cross(R - cj, -fi);
      const double lever = std::max((R - ci).norm(), (R - cj).norm());
      const double errs[] = {
          std::abs(r.list.area[0] - c.area) / c.area,
          (Vec2(r.list.rx[0], r.list.ry[0]) - R).norm() / 0.01,
          (Vec2(r.list.nx[0], r.list.ny[0]) - n).norm(),
          std::abs(r.list.fn[0] + magnitude) / magnitude,
          (Vec2(r.f[0], r.f[2]) - fi).norm() / magnitude,
          (Vec2(r.f[1], r.f[3]) + fi).norm() / magnitude,  // j: equal and opposite
          std::abs(r.f[4] - ti) / (magnitude * lever),
          std::abs(r.f[5] - tj) / (magnitude * lever),
      };
      for (double e : errs) {
        worst = std::max(worst, e);
        EXPECT_LT(e, 1e-12) << c.name << ", turn " << w;
      }
      // Exactly opposite forces (the library subtracts the same numbers).
      EXPECT_EQ(r.f[0], -r.f[1]);
      EXPECT_EQ(r.f[2], -r.f[3]);
    }
  }
  std::printf("[ contacts ] two squares against the hand computation: worst relative error %.2e\n", worst);
}

TEST(DemContacts, LeverArmTorqueOfTheOffCentreContact) {
  // The second case in numbers: τ_i = y_off·Y·A·h/L_c (counter-clockwise for y_off > 0, since i is
  // pushed along −x at a point above its centre), τ_j = 0.
  const Case c = hand_cases()[1];
  Material mat;
  const CellMesh mesh = rectangles(c.sizes, {Vec2(0, 0), c.cj}, 0.01);
  const Bodies bodies = frac::dem::make_bodies(mesh, mat);
  const LibResult r = library(mesh, bodies, state({Vec2(0, 0), c.cj}, {0, 0}), std::vector<double>(6, 0.0),
                              {kY, kH, 0, 0, 0}, false, false);
  const double inv_lc = 0.5 * (1 / bodies.diameter[0] + 1 / bodies.diameter[1]);
  const double f = kY * c.area * kH * inv_lc;
  EXPECT_GT(r.f[4], 0);
  EXPECT_LT(std::abs(r.f[4] - c.R.y() * f) / (c.R.y() * f), 1e-12);
  EXPECT_LT(std::abs(r.f[5]) / (c.R.y() * f), 1e-12);
}

TEST(DemContacts, DampingAndFrictionAgainstTheNote) {
  // Moving bodies (translations and spins), the three terms together, in both friction regimes: viscous
  // (μ large, F_t = m_eff γ_T |v_t|) and Coulomb (μ small, |F_t| = μ|F_n|). Power: the terms' powers sum
  // to Σ F·v + τ ω over the bodies; damping and friction never deliver energy.
  Material mat;
  const ContactParameters base{kY, kH, 0, 0, 0};
  frac::Rng rng(23);
  int viscous = 0, coulomb = 0;
  for (const Case& c : hand_cases()) {
    const CellMesh mesh = rectangles(c.sizes, {Vec2(0, 0), c.cj}, 0.01);
    const Bodies bodies = frac::dem::make_bodies(mesh, mat);
    for (int t = 0; t < 40; ++t) {
      const double w = (rng.uniform() - 0.5) * 2 * kPi;
      const Vec2 ci(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)), cj = ci + rot(c.cj, w);
      const auto q = state({ci, cj}, {w, w});
      std::vector<double> v(6);
      for (double& x : v) x = rng.uniform(-5, 5);
      v[4] *= 100;  // spins of a few hundred rad/s: surface speeds comparable to the translations
      v[5] *= 100;
      ContactParameters p = base;
      p.gamma_n = rng.uniform(1e3, 1e5);
      p.gamma_t = rng.uniform(1e3, 1e5);
      p.friction = t % 2 ? 10.0 : 0.02;
      const LibResult r = library(mesh, bodies, q, v, p, true, true);
      ASSERT_EQ(r.list.size(), 1u);
      const Vec2 R = ci + rot(c.R, w), n = rot(c.n, w);
      const Kin ki{ci, Vec2(v[0], v[2]), v[4], bodies.mass[0], bodies.diameter[0]};
      const Kin kj{cj, Vec2(v[1], v[3]), v[5], bodies.mass[1], bodies.diameter[1]};
      const PairForce x = note_pair(ki, kj, R, n, c.area, p.gamma_n, p.gamma_t, p.friction);
      // Regime actually exercised.
      const Vec2 vrel = kj.v + kj.w * perp(R - kj.c) - ki.v - ki.w * perp(R - ki.c);
      const double meff = ki.m * kj.m / (ki.m + kj.m);
      (meff * p.gamma_t * std::abs(vrel.dot(perp(n))) < p.friction * std::abs(x.fn) ? viscous : coulomb)++;
      const double scale = x.fi.norm() + std::abs(x.fn);
      const double lever = std::max((R - ci).norm(), (R - cj).norm());
      EXPECT_LT((Vec2(r.f[0], r.f[2]) - x.fi).norm() / scale, 1e-12) << c.name;
      EXPECT_LT((Vec2(r.f[1], r.f[3]) + x.fi).norm() / scale, 1e-12) << c.name;
      EXPECT_LT(std::abs(r.f[4] - x.ti) / (scale * lever), 1e-12) << c.name;
      EXPECT_LT(std::abs(r.f[5] - x.tj) / (scale * lever), 1e-12) << c.name;
      EXPECT_LT(std::abs(r.list.fn[0] - x.fn) / scale, 1e-12);
      double fv = 0, fv_scale = 0;
      for (int k = 0; k < 6; ++k) {
        fv += r.f[k] * v[k];
        fv_scale += std::abs(r.f[k] * v[k]);
      }
      EXPECT_LT(std::abs(r.power[0] + r.power[1] + r.power[2] - fv), 1e-12 * fv_scale);
      EXPECT_LE(r.power[1], 0.0) << "damping delivered energy";
      EXPECT_LE(r.power[2], 0.0) << "friction delivered energy";
    }
  }
  EXPECT_GT(viscous, 10);
  EXPECT_GT(coulomb, 10);
}

// A contact law that only this test knows: adhesion proportional to the overlap area, F_n = +k·A (pulling i
// towards j). It joins the engine as one struct and one row of a table, and a scene file switches it on by its
// row's key; nothing else changes.
struct Adhesion {
  double k;  // N/m^2
  frac::dem::LawForce operator()(const frac::dem::ContactState& s) const { return {k * s.area, 0.0}; }
};

TEST(DemContacts, ALawOfATestJoinsTheEngineAsOneStructAndOneRow) {
  constexpr double kAdhesion = 3e6;
  frac::dem::ContactLawTable table = frac::dem::contact_law_table();
  table.push_back({"adhesion", [](const Material&) { return frac::dem::contact_law(Adhesion{kAdhesion}); }});
  const Case c = hand_cases()[0];
  const CellMesh mesh = rectangles(c.sizes, {Vec2(0, 0), c.cj}, 0.01);
  const auto q = state({Vec2(0, 0), c.cj}, {0, 0});
  const std::vector<double> v{0.2, -0.3, 0.1, 0.4, 20, -10};
  // The same scene file with and without the new law's switch.
  const std::string text = "[material]\ngamma_n = 1e4\n[physics]\nbeams = off\nbreaking = off\ndamping = on\n";
  frac::Scene plain_scene = frac::Scene::parse(text, "plain.ini");
  frac::Scene adhesive_scene = frac::Scene::parse(text + "adhesion = on\n", "adhesive.ini");
  const frac::dem::DemScene plain_dem = frac::dem::read_dem_scene(plain_scene, table);
  const frac::dem::DemScene adhesive_dem = frac::dem::read_dem_scene(adhesive_scene, table);
  const Material& mat = plain_dem.material;
  Model plain(mesh, mat, plain_dem.physics, table);
  Model adhesive(mesh, mat, adhesive_dem.physics, table);
  // (The table the tools use has no such row: the key is unknown to their scenes.)
  frac::Scene stray = frac::Scene::parse(text + "adhesion = on\n", "stray.ini");
  frac::dem::read_dem_scene(stray);
  EXPECT_THROW(stray.check_all_used(), frac::UsageError);
  EXPECT_EQ(adhesive.terms(), (std::vector<std::string>{"contact", "damping", "adhesion"}));
  std::vector<double> a(6);
  plain.accelerations(0, q, v, a);
  adhesive.accelerations(0, q, v, a);
  ASSERT_EQ(adhesive.contacts().size(), 1u);
  // The added force: k·A along n on i, the opposite on j, at R (torques r × F about each centroid).
  const Vec2 f = kAdhesion * c.area * c.n;
  const double want[6] = {f.x(), -f.x(), f.y(), -f.y(), cross(c.R, f), -cross(c.R - c.cj, f)};
  const double scale = std::abs(adhesive.forces()[0]) + f.norm();
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_NEAR(adhesive.forces()[k] - plain.forces()[k], want[k], 1e-12 * scale * (k >= 4 ? 0.01 : 1)) << k;
  // Its power, F·(v_i(R) − v_j(R)), and the other laws' unchanged.
  const Vec2 vi = Vec2(v[0], v[2]) + v[4] * perp(c.R), vj = Vec2(v[1], v[3]) + v[5] * perp(c.R - c.cj);
  EXPECT_NEAR(adhesive.law_power(2), f.dot(vi - vj), 1e-12 * f.norm() * (vi - vj).norm());
  EXPECT_EQ(adhesive.law_power(0), plain.law_power(0));
  EXPECT_EQ(adhesive.law_power(1), plain.law_power(1));
  // A model cannot take a law its table lacks.
  EXPECT_THROW(Model(mesh, mat, adhesive_dem.physics), frac::UsageError);
}

TEST(DemContacts, DampingAddsToTheRepulsionWhileApproaching) {
  // §3 [fix]: while approaching (v_n < 0) the dashpot adds to the repulsion; while separating it
  // lessens it. Friction drags i along with j's sliding.
  const Case c = hand_cases()[2];
  Material mat;
  const CellMesh mesh = rectangles(c.sizes, {Vec2(0, 0), c.cj}, 0.01);
  const Bodies bodies = frac::dem::make_bodies(mesh, mat);
  const auto q = state({Vec2(0, 0), c.cj}, {0, 0});
  const ContactParameters p{kY, kH, 1e4, 1e4, 0.5};
  const double elastic = library(mesh, bodies, q, std::vector<double>(6, 0.0), p, false, false).f[0];
  ASSERT_LT(elastic, 0);
  // j moving toward i (−x): stronger push on i (more negative x force).
  const auto approach = library(mesh, bodies, q, {0, -1, 0, 0, 0, 0}, p, true, false);
  EXPECT_LT(approach.f[0], elastic);
  const auto separate = library(mesh, bodies, q, {0, 1, 0, 0, 0, 0}, p, true, false);
  EXPECT_GT(separate.f[0], elastic);
  // j sliding up (+y) along the contact: friction pulls i up, j down.
  const auto slide = library(mesh, bodies, q, {0, 0, 0, 1, 0, 0}, p, true, true);
  EXPECT_GT(slide.f[2], 0);
  EXPECT_LT(slide.f[3], 0);
}

// A random-lattice sample with every cell displaced and turned at random, so that many pairs overlap.
struct Sample {
  CellMesh mesh;
  std::vector<double> q, v;
};
Sample random_overlaps(std::uint64_t seed, double jiggle) {
  frac::mesh::RandomLatticeOptions o;
  o.shape = "rect";
  o.nx = 16;
  o.ny = 16;
  o.width = o.height = 16 * 0.0107;
  o.seed = seed;
  Sample s{frac::mesh::make_random_lattice(o), {}, {}};
  const std::size_t n = s.mesh.cells();
  const double g = s.mesh.spacing;
  frac::Rng rng(seed + 100);
  s.q.assign(3 * n, 0.0);
  s.v.assign(3 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    s.q[k] = s.mesh.centroid[k].x() + jiggle * g * rng.uniform(-1, 1);
    s.q[n + k] = s.mesh.centroid[k].y() + jiggle * g * rng.uniform(-1, 1);
    s.q[2 * n + k] = jiggle * rng.uniform(-1, 1);
    s.v[k] = rng.uniform(-2, 2);
    s.v[n + k] = rng.uniform(-2, 2);
    s.v[2 * n + k] = rng.uniform(-200, 200);
  }
  return s;
}

// By brute force at state q: the pairs whose bounding circles overlap, and those whose polygons overlap
// (clipped directly; a polygon never leaves its circle).
struct BruteForcePairs {
  std::size_t circles = 0;
  std::set<std::pair<int, int>> overlapping;
};
BruteForcePairs brute_force_pairs(const CellMesh& mesh, const Bodies& bodies, const std::vector<double>& q) {
  const std::size_t n = mesh.cells();
  std::vector<std::vector<Vec2>> world(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double c = std::cos(q[2 * n + k]), sn = std::sin(q[2 * n + k]);
    for (const Vec2& p : mesh.polygon(k))
      world[k].emplace_back(q[k] + c * p.x() - sn * p.y(), q[n + k] + sn * p.x() + c * p.y());
  }
  BruteForcePairs out;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double dx = q[j] - q[i], dy = q[n + j] - q[n + i];
      const double reach = bodies.bound_radius[i] + bodies.bound_radius[j];
      if (!(dx * dx + dy * dy < reach * reach)) continue;  // (the search's own circle test)
      ++out.circles;
      const auto g = frac::geometry::convex_overlap(world[i], world[j], Vec2(q[i], q[n + i]), Vec2(q[j], q[n + j]),
                                                    bodies.length_scale);
      if (g.kind != frac::geometry::ContactGeometry::Kind::none)
        out.overlapping.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  return out;
}

TEST(DemContacts, SearchFindsEveryOverlappingPair) {
  // The cell list with bounding-circle culling against all N(N−1)/2 pairs.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const Sample s = random_overlaps(seed, 0.15);
    Material mat;
    const Bodies bodies = frac::dem::make_bodies(s.mesh, mat);
    ContactSearch search(s.mesh, bodies);
    ContactList list;
    search.find(s.q, list);
    std::set<std::pair<int, int>> found;
    for (std::size_t k = 0; k < list.size(); ++k) found.insert({list.i[k], list.j[k]});
    EXPECT_EQ(found.size(), list.size()) << "a pair listed twice";
    const BruteForcePairs brute = brute_force_pairs(s.mesh, bodies, s.q);
    EXPECT_EQ(found, brute.overlapping);
    EXPECT_EQ(static_cast<std::size_t>(list.candidate_pairs), brute.circles);
    EXPECT_GT(list.size(), s.mesh.cells()) << "the test needs many overlaps";
  }
}

// The neighbour list kept from state to state (rebuilt only when two cells may together have moved by more
// than its skin) misses no pair whose bounding circles overlap, let alone one whose polygons do: every cell
// drifting at up to 0.05 lattice spacings a step (pairs closing at up to 0.14) and turning by up to 0.3 rad a
// step (turning cannot take a polygon out of its circle), against brute force at every state; on one and on
// two and three threads. (A rule that let each cell move by the whole skin misses circle pairs here.)
TEST(DemContacts, NeighbourListKeptAcrossStatesMissesNoPair) {
  for (const int threads : {1, 2, 3}) {
    const frac::test::ThreadCount thread_count(threads);
    Sample s = random_overlaps(4, 0.02);
    const std::size_t n = s.mesh.cells();
    const double g = s.mesh.spacing;
    Material mat;
    const Bodies bodies = frac::dem::make_bodies(s.mesh, mat);
    ContactSearch search(s.mesh, bodies);
    ContactList list;
    frac::Rng rng(99);
    std::vector<double> drift(3 * n);
    for (std::size_t k = 0; k < n; ++k) {
      const double speed = 0.05 * g * rng.uniform(0, 1), angle = 2 * std::numbers::pi * rng.uniform(0, 1);
      drift[k] = speed * std::cos(angle);
      drift[n + k] = speed * std::sin(angle);
      drift[2 * n + k] = 0.3 * rng.uniform(-1, 1);
    }
    const int states = 60;
    for (int step = 0; step < states; ++step) {
      search.find(s.q, list);
      std::set<std::pair<int, int>> found;
      for (std::size_t k = 0; k < list.size(); ++k) found.insert({list.i[k], list.j[k]});
      const BruteForcePairs brute = brute_force_pairs(s.mesh, bodies, s.q);
      ASSERT_EQ(static_cast<std::size_t>(list.candidate_pairs), brute.circles)
          << "state " << step << ", " << threads << " threads";
      ASSERT_EQ(found, brute.overlapping) << "state " << step << ", " << threads << " threads";
      for (std::size_t k = 0; k < 3 * n; ++k) s.q[k] += drift[k];
    }
    // The list was kept between rebuilds (else the test shows nothing).
    EXPECT_LT(search.rebuilds(), states / 2);
  }
}

// The search, the three terms and the sum over the contacts on one, two and three threads: the same list, entry by
// entry, and the forces, torques and powers the same bits, after forces already on the cells (as the beams leave
// them) and for every term.
// (More than 256 contacts: fewer run on one thread whatever the thread count.)
TEST(DemContacts, ContactForcesAreSummedInContactOrderOnAnyThreadCount) {
  for (std::uint64_t seed : {1u, 2u}) {
    const Sample s = random_overlaps(seed, 0.15);
    Material mat;
    mat.gamma_n = mat.gamma_t = 5e3;
    mat.friction = 0.3;
    const ContactParameters p{kY, kH, mat.gamma_n, mat.gamma_t, mat.friction};
    const Bodies bodies = frac::dem::make_bodies(s.mesh, mat);
    const std::size_t n = s.mesh.cells();
    frac::Rng rng(seed + 7);
    std::vector<double> f0(3 * n);
    for (double& x : f0) x = rng.uniform(-1, 1);
    std::vector<double> forces[3];
    double powers[3][3];
    std::vector<std::array<double, 4>> entries[3];  // each contact's cells, area and normal, in list order
    for (int threads : {1, 2, 3}) {
      const frac::test::ThreadCount thread_count(threads);
      ContactSearch search(s.mesh, bodies);
      ContactList list;
      search.find(s.q, list);
      ASSERT_GT(list.size(), 256u) << "the test needs the parallel path";
      for (std::size_t k = 0; k < list.size(); ++k)
        entries[threads - 1].push_back(
            {static_cast<double>(list.i[k]), static_cast<double>(list.j[k]), list.area[k], list.nx[k]});
      auto& f = forces[threads - 1];
      f = f0;
      const std::vector<double> power = law_powers(list, p, bodies, s.q, s.v, {"contact", "damping", "friction"});
      for (int t = 0; t < 3; ++t) powers[threads - 1][t] = power[static_cast<std::size_t>(t)];
      frac::dem::add_contact_forces(list, n, s.q, f);
    }
    for (int threads : {2, 3}) {
      const auto u = static_cast<std::size_t>(threads - 1);
      ASSERT_EQ(entries[u], entries[0]) << "seed " << seed << ": the list on " << threads << " threads";
      for (std::size_t k = 0; k < 3 * n; ++k)
        ASSERT_EQ(forces[0][k], forces[u][k])
            << "seed " << seed << ", coordinate " << k << ", " << threads << " threads";
      for (int t = 0; t < 3; ++t)
        EXPECT_EQ(powers[0][t], powers[u][t]) << "term " << t << ", " << threads << " threads";
    }
  }
}

// Wraps the model and checks, at every force evaluation, that the pair interactions sum to zero force
// and zero torque about several points.
class Checked final : public frac::dynamics::System {
 public:
  explicit Checked(Model& m) : m_(m) {}
  void accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override {
    m_.accelerations(t, q, v, a);
    const std::size_t n = m_.bodies().n;
    const auto f = m_.forces();
    const Vec2 points[] = {Vec2(0, 0), Vec2(0.08, 0.09), Vec2(-3.0, 5.0)};
    double fx = 0, fy = 0, fs = 0;
    for (std::size_t k = 0; k < n; ++k) {
      fx += f[k];
      fy += f[n + k];
      fs += std::hypot(f[k], f[n + k]);
    }
    if (fs == 0) return;
    worst_force = std::max(worst_force, std::hypot(fx, fy) / fs);
    for (const Vec2& p : points) {
      double tau = 0, ts = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const double rx = q[k] - p.x(), ry = q[n + k] - p.y();
        const double c = rx * f[n + k] - ry * f[k];
        tau += f[2 * n + k] + c;
        ts += std::abs(f[2 * n + k]) + std::hypot(rx, ry) * std::hypot(f[k], f[n + k]);
      }
      worst_torque = std::max(worst_torque, std::abs(tau) / ts);
    }
    ++evaluations;
  }
  double worst_force = 0, worst_torque = 0;
  long evaluations = 0;

 private:
  Model& m_;
};

// Linear momentum Σ m v and its scale Σ m |v|.
std::pair<Vec2, double> momentum(const Model& m, std::span<const double> v) {
  const std::size_t n = m.bodies().n;
  Vec2 p(0, 0);
  double s = 0;
  for (std::size_t k = 0; k < n; ++k) {
    p += m.bodies().mass[k] * Vec2(v[k], v[n + k]);
    s += m.bodies().mass[k] * std::hypot(v[k], v[n + k]);
  }
  return {p, s};
}

// Validation E8 and the acceptance item: contacts, damping and friction on (and beams, the other pair
// interaction), random overlapping configurations, a run of 1000 steps. At every evaluation
// |Σ F| ≤ 1e-12 Σ|F| and |Σ (τ + (c − P) × F)| ≤ 1e-12 of Σ(|τ| + |c − P||F|) about three points P:
// each pair force is applied to both bodies as the same numbers with opposite signs at one point, so
// only the rounding of the sums remains (~N·1e-16 at worst, N ≈ 256 bodies). Momentum: both schemes
// are linear in the accelerations, so Σ m v changes only by the rounding of Σ F (≈1e-16 relative per
// step); over 1000 steps that stays below 1e-12 of Σ m|v|, and the acceptance bound is 1e-10.
TEST(DemContacts, PairInteractionsConserveMomentumOnRandomOverlaps) {
  for (auto kind : {frac::dynamics::IntegratorKind::gear5, frac::dynamics::IntegratorKind::verlet}) {
    for (std::uint64_t seed : {kind == frac::dynamics::IntegratorKind::gear5 ? 4u : 5u}) {
      Sample s = random_overlaps(seed, 0.1);
      Material mat;
      mat.gamma_n = 5e3;  // γ_eff·dt ≲ 0.05 at this dt: inside gear5's damping stability (γ·dt < 0.163)
      mat.gamma_t = 5e3;
      mat.friction = 0.3;
      Physics ph;
      ph.contacts = ph.beams = true;
      ph.laws = {"contact", "damping", "friction"};
      ph.breaking = false;
      Model model(s.mesh, mat, ph);
      const double dt = frac::dem::choose_time_step(s.mesh, mat, ph, kind, 0, 0.3, false).dt;
      Checked sys(model);
      auto in = frac::dynamics::make_integrator(kind);
      in->start(sys, 0.0, dt, s.q, s.v);
      const auto [p0, scale0] = momentum(model, in->v());
      const auto ke0 = model.kinetic_energy(in->v());
      double scale = scale0, drift = 0;
      std::size_t max_contacts = 0;
      for (int step = 0; step < 1000; ++step) {
        in->step(sys);
        const auto [p, sc] = momentum(model, in->v());
        scale = std::max(scale, sc);
        drift = std::max(drift, (p - p0).norm());
        max_contacts = std::max(max_contacts, model.contacts().size());
      }
      const auto ke1 = model.kinetic_energy(in->v());
      std::printf(
          "[ contacts ] %s seed %lu, dt %.3g s: %ld evaluations, up to %zu contacts; worst |ΣF|/Σ|F| = %.2e, "
          "worst torque residual = %.2e, momentum drift = %.2e of Σm|v|; kinetic energy %.3g -> %.3g J\n",
          std::string(frac::dynamics::name(kind)).c_str(), static_cast<unsigned long>(seed), dt, sys.evaluations,
          max_contacts, sys.worst_force, sys.worst_torque, drift / scale, ke0[0] + ke0[1], ke1[0] + ke1[1]);
      EXPECT_GT(max_contacts, s.mesh.cells() / 2);
      EXPECT_GT(model.calls("friction"), 1000);
      EXPECT_LT(sys.worst_force, 1e-12);
      EXPECT_LT(sys.worst_torque, 1e-12);
      EXPECT_LT(drift / scale, 1e-10);
    }
  }
}

}  // namespace
