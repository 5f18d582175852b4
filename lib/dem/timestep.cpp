#include "dem/timestep.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "dem/beam.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_laws.hpp"

namespace frac::dem {

namespace {
// Largest eigenvalue of a symmetric positive semidefinite operator by power iteration from a fixed
// pseudo-random start (every mode present); converges from below.
template <class Apply>
double largest_eigenvalue(std::size_t size, const Apply& apply) {
  std::vector<double> x(size), y(size);
  std::uint64_t s = 0x9e3779b97f4a7c15ULL;
  for (auto& v : x) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    v = static_cast<double>(s >> 11) * 0x1.0p-53 - 0.5;
  }
  double lambda = 0;
  for (int it = 0; it < 400; ++it) {
    double norm = 0;
    for (double v : x) norm += v * v;
    norm = std::sqrt(norm);
    if (norm == 0) return 0.0;
    for (double& v : x) v /= norm;
    apply(x, y);
    double r = 0;
    for (std::size_t k = 0; k < x.size(); ++k) r += x[k] * y[k];
    const double previous = lambda;
    lambda = r;
    x.swap(y);
    if (it > 20 && std::abs(lambda - previous) < 1e-6 * lambda) break;
  }
  return std::max(lambda, 0.0);
}

std::vector<double> inverse_sqrt_masses(const Bodies& bodies) {
  const std::size_t n = bodies.n;
  std::vector<double> w(3 * n);
  for (std::size_t k = 0; k < n; ++k) {
    w[k] = w[n + k] = 1.0 / std::sqrt(bodies.mass[k]);
    w[2 * n + k] = 1.0 / std::sqrt(bodies.inertia[k]);
  }
  return w;
}
}  // namespace

double max_damping_rate(const mesh::CellMesh& mesh, const Material& material, const Physics& physics) {
  const auto [gn, gt] = dashpot_rates(contact_law_table(), physics.laws, material);
  if (!physics.contacts || (gn == 0 && gt == 0) || mesh.beams() == 0) return 0.0;
  const Bodies bodies = make_bodies(mesh, material);
  const std::size_t n = bodies.n;
  const auto w = inverse_sqrt_masses(bodies);
  // Each beam's geometry and dashpot constants, once (the power iteration applies the operator hundreds of
  // times).
  struct Dashpot {
    std::size_t i, j;
    double ex, ey, h, cn, ct;  // axis, half length, m_eff·γ_N and m_eff·γ_T
  };
  std::vector<Dashpot> dashpots(mesh.beams());
  for (std::size_t b = 0; b < mesh.beams(); ++b) {
    const auto i = static_cast<std::size_t>(mesh.beam[b][0]), j = static_cast<std::size_t>(mesh.beam[b][1]);
    const auto d = mesh.centroid[j] - mesh.centroid[i];
    const double l = d.norm();
    const double m_eff = bodies.mass[i] * bodies.mass[j] / (bodies.mass[i] + bodies.mass[j]);
    dashpots[b] = {i, j, d.x() / l, d.y() / l, 0.5 * l, m_eff * gn, m_eff * gt};
  }
  const double lambda = largest_eigenvalue(3 * n, [&](const std::vector<double>& x, std::vector<double>& y) {
    std::fill(y.begin(), y.end(), 0.0);
    for (const Dashpot& p : dashpots) {
      const std::size_t i = p.i, j = p.j;
      const double ex = p.ex, ey = p.ey, h = p.h;
      // Velocities of i and j at the midpoint R = c_i + (l/2)e, from u = M^{-1/2} x.
      const double vxi = x[i] * w[i], vyi = x[n + i] * w[n + i], oi = x[2 * n + i] * w[2 * n + i];
      const double vxj = x[j] * w[j], vyj = x[n + j] * w[n + j], oj = x[2 * n + j] * w[2 * n + j];
      const double rel_n = (vxj - vxi) * ex + (vyj - vyi) * ey;
      const double rel_t = -(vxj - vxi) * ey + (vyj - vyi) * ex - h * (oi + oj);
      const double fn = p.cn * rel_n, ft = p.ct * rel_t;  // force on i along e and t
      const double fx = fn * ex - ft * ey, fy = fn * ey + ft * ex;
      const double torque = h * ft;  // (R − c_i) × F_i = (l/2) F_t, and the same on j
      y[i] -= fx * w[i];
      y[n + i] -= fy * w[n + i];
      y[j] += fx * w[j];
      y[n + j] += fy * w[n + j];
      y[2 * n + i] -= torque * w[2 * n + i];
      y[2 * n + j] -= torque * w[2 * n + j];
    }
  });
  return lambda * 1.02;
}

double max_eigenfrequency(const mesh::CellMesh& mesh, const Material& material, const Physics& physics) {
  const Bodies bodies = make_bodies(mesh, material);
  const std::size_t n = bodies.n, nb = mesh.beams();
  // Floor for contacts between cells that are not mesh neighbours (fragments that meet, hand-built
  // scenes): a pair of equal cells touching along a contact line as long as their equal-area diameter
  // r, k = Y·h·r/L_c = Y·h, m_eff = m/2, so ω² = 2·Y·h/m for the lightest cell.
  double floor = 0;
  if (physics.contacts)
    for (std::size_t k = 0; k < n; ++k)
      floor = std::max(floor, std::sqrt(2 * material.grain_modulus * material.thickness / bodies.mass[k]));
  if (n == 0 || nb == 0) return floor;
  const auto inv_sqrt_m = inverse_sqrt_masses(bodies);
  struct Pair {
    std::size_t i, j;
    double ex, ey, l0, axial;
    BeamStiffness k;
  };
  std::vector<Pair> pairs(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const auto i = static_cast<std::size_t>(mesh.beam[b][0]), j = static_cast<std::size_t>(mesh.beam[b][1]);
    const auto d = mesh.centroid[j] - mesh.centroid[i];
    const double l0 = d.norm();
    BeamStiffness k{0, 0, 0};
    if (physics.beams)
      k = beam_stiffness(l0, mesh.beam_section[b], material.thickness, material.beam_modulus, material.shear_ratio);
    double axial = k.alpha;
    if (physics.contacts)
      axial += material.grain_modulus * material.thickness * mesh.beam_section[b] * 0.5 *
               (1 / bodies.diameter[i] + 1 / bodies.diameter[j]);
    pairs[b] = {i, j, d.x() / l0, d.y() / l0, l0, axial, k};
  }
  // y = M^{-1/2} K M^{-1/2} x, with K u = −F(u) of the linearised pair laws.
  auto apply = [&](const std::vector<double>& x, std::vector<double>& y) {
    std::vector<double> u(3 * n);
    for (std::size_t k = 0; k < 3 * n; ++k) u[k] = x[k] * inv_sqrt_m[k];
    std::fill(y.begin(), y.end(), 0.0);
    for (const Pair& p : pairs) {
      const double dx = u[p.j] - u[p.i], dy = u[n + p.j] - u[n + p.i];
      const double da = dx * p.ex + dy * p.ey;   // axial stretch
      const double dt = -dx * p.ey + dy * p.ex;  // transverse offset along t = ẑ × e
      const double ti = u[2 * n + p.i] - dt / p.l0, tj = u[2 * n + p.j] - dt / p.l0;
      const double l02 = p.l0 * p.l0;
      const double mi = -(p.k.beta * l02 / 2) * tj + p.k.delta * l02 * (tj - ti);
      const double mj = -(p.k.beta * l02 / 2) * ti + p.k.delta * l02 * (ti - tj);
      const double q = (mi + mj) / p.l0;
      const double fx = p.axial * da * p.ex - q * p.ey, fy = p.axial * da * p.ey + q * p.ex;  // force on i
      y[p.i] -= fx;
      y[n + p.i] -= fy;
      y[p.j] += fx;
      y[n + p.j] += fy;
      y[2 * n + p.i] -= mi;
      y[2 * n + p.j] -= mj;
    }
    for (std::size_t k = 0; k < 3 * n; ++k) y[k] *= inv_sqrt_m[k];
  };
  const double lambda = largest_eigenvalue(3 * n, apply);
  return std::max(floor, std::sqrt(std::max(lambda, 0.0)) * 1.02);
}

TimeStep choose_time_step(const mesh::CellMesh& mesh, const Material& material, const Physics& physics,
                          dynamics::IntegratorKind kind, double dt_requested, double safety, bool allow_unstable) {
  TimeStep ts{};
  ts.omega_max = max_eigenfrequency(mesh, material, physics);
  ts.gamma_max = max_damping_rate(mesh, material, physics);
  const double limit = dynamics::stability_limit(kind);
  const double damping = dynamics::damping_limit(kind);
  ts.bound = ts.omega_max > 0 ? limit / ts.omega_max : 1e-3;
  if (ts.gamma_max > 0) ts.bound = std::min(ts.bound, damping / ts.gamma_max);
  if (dt_requested <= 0) {
    ts.dt = safety * ts.bound;
  } else {
    ts.dt = dt_requested;
    if (dt_requested > ts.bound && !allow_unstable) {
      std::ostringstream msg;
      msg.precision(3);
      msg << "integrator.dt = " << dt_requested << " s is above the stability bound " << ts.bound << " s of "
          << dynamics::name(kind) << " (ω_max = " << ts.omega_max << " rad/s, ω·dt ≤ " << limit;
      if (ts.gamma_max > 0) msg << "; damping rate γ_max = " << ts.gamma_max << " 1/s, γ·dt ≤ " << damping;
      msg << "); use a smaller dt, dt = auto, or integrator.allow_unstable = on";
      throw UsageError(msg.str());
    }
  }
  return ts;
}

}  // namespace frac::dem
