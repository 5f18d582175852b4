#include "rubber/probe.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "mesh/triangular_lattice.hpp"
#include "rubber/lattice.hpp"

namespace frac::rubber {

Patch make_patch(const BondLaw& law, double node_mass, std::int64_t nx, std::int64_t ny, bool rows_along_x,
                 const Eigen::Matrix2d& F) {
  mesh::TriangularLatticeOptions opt;
  opt.nx = nx;
  opt.ny = ny;
  opt.spacing = law.params.spacing;
  opt.rows_along = rows_along_x ? "x" : "y";
  const mesh::NodeMesh m = mesh::make_triangular_lattice(opt);
  ModelOptions mo;
  mo.law = law;
  mo.node_mass = node_mass;
  mo.threads = 1;
  Patch p;
  p.F = F;
  p.model = std::make_unique<Model>(build_lattice(m, true, true), mo);
  p.model->set_box(F);
  const std::size_t n = m.position.size();
  p.q.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d x = F * m.position[i];
    p.q[i] = x.x();
    p.q[n + i] = x.y();
  }
  return p;
}

double mode_omega2(Patch& patch, const Eigen::Vector2d& k_ref, const Eigen::Vector2d& U) {
  Model& model = *patch.model;
  const Lattice& L = model.lattice();
  const std::size_t n = L.n;
  const double eps = 1e-5 * L.spacing;
  std::vector<double> delta(2 * n), qp(patch.q), qm(patch.q), fp(2 * n), fm(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double c = std::cos(k_ref.x() * L.rx[i] + k_ref.y() * L.ry[i]);
    delta[i] = eps * U.x() * c;
    delta[n + i] = eps * U.y() * c;
  }
  for (std::size_t k = 0; k < 2 * n; ++k) {
    qp[k] += delta[k];
    qm[k] -= delta[k];
  }
  model.forces(qp, fp);
  model.forces(qm, fm);
  double num = 0, den = 0;
  for (std::size_t k = 0; k < 2 * n; ++k) {
    num += delta[k] * (fp[k] - fm[k]);
    den += delta[k] * delta[k];
  }
  return -num / (2 * model.node_mass() * den);
}

LatticeSpeeds lattice_speeds(const BondLaw& law, double node_mass, double lx, double ly, char direction,
                             bool rows_along_x, double wavelengths) {
  const double h = std::sqrt(3.0) / 2;
  const bool along_x = direction == 'x';
  // Nodes along the probe direction so that the box is about `wavelengths` spacings long.
  std::int64_t nx = 4, ny = 4;
  double box = 0;
  const double d = law.params.spacing;
  if (along_x) {
    if (rows_along_x) {
      nx = std::max<std::int64_t>(3, std::llround(wavelengths));
      box = static_cast<double>(nx) * d;
    } else {
      nx = 2 * std::max<std::int64_t>(2, std::llround(wavelengths / h / 2));
      box = static_cast<double>(nx) * h * d;
    }
  } else {
    if (rows_along_x) {
      ny = 2 * std::max<std::int64_t>(2, std::llround(wavelengths / h / 2));
      box = static_cast<double>(ny) * h * d;
    } else {
      ny = std::max<std::int64_t>(3, std::llround(wavelengths));
      box = static_cast<double>(ny) * d;
    }
  }
  const Eigen::Matrix2d F{{lx, 0}, {0, ly}};
  Patch patch = make_patch(law, node_mass, nx, ny, rows_along_x, F);
  const Eigen::Vector2d e_along = along_x ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d e_across = along_x ? Eigen::Vector2d(0, 1) : Eigen::Vector2d(1, 0);
  const double k1 = 2 * std::numbers::pi / box, k2 = 2 * k1;
  const double stretch = along_x ? lx : ly;
  auto speed = [&](const Eigen::Vector2d& U, double& omega2_k1) {
    omega2_k1 = mode_omega2(patch, k1 * e_along, U);
    const double w2 = mode_omega2(patch, k2 * e_along, U);
    const double c1 = omega2_k1 / (k1 * k1), c2 = w2 / (k2 * k2);
    const double c0 = (4 * c1 - c2) / 3;
    return c0 >= 0 && omega2_k1 >= 0 ? stretch * std::sqrt(c0) : std::numeric_limits<double>::quiet_NaN();
  };
  LatticeSpeeds s;
  s.longitudinal = speed(e_along, s.longitudinal_omega2);
  s.transverse = speed(e_across, s.transverse_omega2);
  s.wavelength = box;
  return s;
}

double omega_max(const BondLaw& law, double node_mass, const Eigen::Matrix2d& F, bool rows_along_x) {
  Patch patch = make_patch(law, node_mass, 12, 12, rows_along_x, F);
  Model& model = *patch.model;
  const std::size_t dof = patch.q.size();
  const double eps = 1e-6 * law.params.spacing;
  Eigen::MatrixXd K(dof, dof);
  std::vector<double> q(patch.q), fp(dof), fm(dof);
  for (std::size_t k = 0; k < dof; ++k) {
    q[k] = patch.q[k] + eps;
    model.forces(q, fp);
    q[k] = patch.q[k] - eps;
    model.forces(q, fm);
    q[k] = patch.q[k];
    for (std::size_t r = 0; r < dof; ++r)
      K(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = -(fp[r] - fm[r]) / (2 * eps);
  }
  const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose()) / model.node_mass();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, Eigen::EigenvaluesOnly);
  const double top = es.eigenvalues().maxCoeff();
  return top > 0 ? std::sqrt(top) : 0.0;
}

}  // namespace frac::rubber
