// The three-body residual (law.three_body_residual = κ; lib/rubber/three_body_residual.hpp): a failed pair
// keeps κ of its far-field three-body energy. Forces are minus the gradient of the energy (both forms of the
// three-body sum, both weights, bonds in the cut-off, free edges); in the far field (h = 1) energy and
// forces are the paper's; off (no table), nothing changes, bit for bit; and a failing bond's cohesive
// barrier is (1 − κ) of the paper's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <tuple>
#include <vector>

#include "core/rng.hpp"
#include "mesh/triangular_lattice.hpp"
#include "rubber/lattice.hpp"
#include "rubber/model.hpp"
#include "rubber/three_body_residual.hpp"
#include "rubber_test_support.hpp"

namespace {

using namespace frac::rubber;
using Eigen::Matrix2d;
using test::fd_error;
using test::max_abs;

std::unique_ptr<Model> make(const BondLaw& law, double kappa, const Matrix2d& F, double notch = 2.5) {
  frac::mesh::TriangularLatticeOptions o;
  o.nx = 8;
  o.ny = 8;
  o.spacing = 1;
  o.notch = notch;
  Lattice L = build_lattice(frac::mesh::make_triangular_lattice(o));
  ModelOptions mo;
  mo.law = law;
  if (kappa > 0) mo.residual = three_body_residual(law, L, F, kappa);
  return std::make_unique<Model>(std::move(L), mo);
}

const Matrix2d kF{{1.2, 0}, {0, 2.2}};  // far-field bonds 2.3Δ; u_c = 2.75Δ, width 0.05Δ

TEST(RubberResidual, ForcesMatchFiniteDifferences) {
  frac::Rng rng(23);
  for (const auto& [angle, weight] : {std::tuple{"marder", "pair"}, std::tuple{"marder-pairwise", "pair"},
                                      std::tuple{"marder", "all_bonds"}, std::tuple{"marder-pairwise", "all_bonds"}}) {
    const BondLaw law = test::natural_law(1.5, 0.1, 2.75, 0.05, "marder", "fermi", angle, weight);
    auto model = make(law, 0.6, kF);
    auto q = test::deformed(*model, Matrix2d{{1.2, 0}, {0, 2.55}});  // diagonal bonds ≈ 2.65Δ: in the cut-off
    for (double& x : q) x += rng.uniform(-0.08, 0.08);
    EXPECT_LT(fd_error(*model, q), 1e-6) << angle << " " << weight;
  }
}

TEST(RubberResidual, FarFieldIsThePapersAndOffIsBitIdentical) {
  const BondLaw law = test::natural_law(1.5, 0.1, 3.5, 0.05);
  auto paper = make(law, 0, kF, 0), kept = make(law, 0.6, kF, 0);
  const auto q = test::deformed(*paper, kF);
  std::vector<double> fp(q.size()), fk(q.size());
  paper->forces(q, fp);
  kept->forces(q, fk);
  const double scale = max_abs(fp);
  for (std::size_t k = 0; k < q.size(); ++k) EXPECT_NEAR(fk[k], fp[k], 1e-9 * scale);
  const double ep = paper->potential_energy(q).total(), ek = kept->potential_energy(q).total();
  EXPECT_NEAR(ek, ep, 1e-9 * std::abs(paper->potential_energy(q).three_body));
  // An empty table is the paper's law, bit for bit.
  auto none = make(law, 0, kF, 0);
  std::vector<double> fn(q.size());
  none->forces(q, fn);
  EXPECT_EQ(std::memcmp(fn.data(), fp.data(), fn.size() * sizeof(double)), 0);
}

// The energy a bond's removal costs at the far field (its three-body share, with both ends' pairs) is
// (1 − κ) of the paper's.
TEST(RubberResidual, BarrierOfAFailingBondScalesWithOneMinusKappa) {
  const BondLaw law = test::natural_law(1.5, 0.1, 3.5, 0.05);
  const double kappa = 0.6;
  auto paper = make(law, 0, kF, 0), kept = make(law, kappa, kF, 0);
  const auto q = test::deformed(*paper, kF);
  // A diagonal bond in the middle of the sheet (slot 1 of a middle node).
  const std::size_t i = 4 * 8 + 4, b = 3 * i + 1;
  const double p0 = paper->potential_energy(q).three_body, k0 = kept->potential_energy(q).three_body;
  paper->remove_bond(b);
  kept->remove_bond(b);
  const double dp = paper->potential_energy(q).three_body - p0, dk = kept->potential_energy(q).three_body - k0;
  EXPECT_GT(dp, 0);
  EXPECT_NEAR(dk, (1 - kappa) * dp, 1e-9 * dp);
}

}  // namespace
