#include "continuum/mooney_rivlin.hpp"

#include <cmath>
#include <limits>

namespace frac::mr {

namespace {
Mat2 green(const Mat2& F) { return 0.5 * (F.transpose() * F - Mat2::Identity()); }
Mat2 cofactor(const Mat2& F) { return Mat2{{F(1, 1), -F(1, 0)}, {-F(0, 1), F(0, 0)}}; }
}  // namespace

double j1(const Mat2& F) { return green(F).trace(); }
double j2(const Mat2& F) { return green(F).determinant(); }

double energy_per_mass(const Mat2& F, double a, double b) { return a * (j1(F) + b * j2(F)); }

Mat2 piola(const Mat2& F, const Material& m) {
  return m.rho * m.a * ((1 - m.b / 2) * F + (m.b / 2) * F.determinant() * cofactor(F));
}

Mat2 cauchy(const Mat2& F, const Material& m) { return piola(F, m) * F.transpose() / F.determinant(); }

Mat2 acoustic_tensor(const Mat2& F, const Vec2& k_ref, double a, double b) {
  const Vec2 k_lab = F.inverse().transpose() * k_ref;
  const double J = F.determinant();
  return a * ((1 - b / 2) * k_ref.squaredNorm() * Mat2::Identity() + (b / 2) * J * J * k_lab * k_lab.transpose());
}

Speeds speeds(const Mat2& F, const Vec2& n_lab, double a, double b) {
  const Vec2 n = n_lab.normalized();
  const double ft = (F.transpose() * n).squaredNorm();
  const double J = F.determinant();
  const double t2 = a * (1 - b / 2) * ft;
  const double l2 = t2 + a * (b / 2) * J * J;
  Speeds s;
  s.transverse = t2 >= 0 ? std::sqrt(t2) : std::numeric_limits<double>::quiet_NaN();
  s.longitudinal = l2 >= 0 ? std::sqrt(l2) : std::numeric_limits<double>::quiet_NaN();
  return s;
}

double node_mass(double rho, double spacing) { return std::sqrt(3.0) / 2 * rho * spacing * spacing; }
double lattice_A(double node_mass, double a, double spacing) { return node_mass * a / (spacing * spacing); }
double lattice_B(double node_mass, double a, double b, double spacing) {
  const double d2 = spacing * spacing;
  return 9 * node_mass * a * b / (8 * d2 * d2);
}

}  // namespace frac::mr
