#pragma once
// The time step and its stability bound (physics/polygon-dem.md §6). The bound is limit/ω_max, with
// `limit` the largest stable ω·dt of the integrator on a harmonic oscillator (dynamics/integrator)
// and ω_max the largest eigenfrequency of the sample linearised about its reference state: every
// beam (axial, shear and bending, Timoshenko) and, when contacts are on, the overlap stiffness
// Y·h·S/L_c of every touching pair (compression engages both). ω_max comes from power iteration on
// M^{-1/2} K M^{-1/2}, which converges from below; the result is raised by 2% to cover the residual.
// With contacts on, ω_max is at least √(2·Y·h/m) of the lightest cell (two cells meeting along a
// contact line of their own size, whether or not they are mesh neighbours).
#include "dem/material.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

double max_eigenfrequency(const mesh::CellMesh& mesh, const Material& material, const Physics& physics);

// The largest damping rate of the sample (s^-1): the dashpots of normal damping m_eff·γ_N (along the
// line of centres) and of the viscous friction m_eff·γ_T (across it, at the contact point, so it drives
// rotation too) on every touching pair, as the largest eigenvalue of M^{-1/2} C M^{-1/2}. 0 when both
// damping and friction are off.
double max_damping_rate(const mesh::CellMesh& mesh, const Material& material, const Physics& physics);

struct TimeStep {
  double dt;         // s
  double bound;      // s, min(limit/ω_max, damping_limit/γ_max)
  double omega_max;  // rad/s
  double gamma_max;  // s^-1
};

// dt_requested <= 0 means auto: safety × bound. A requested step above the bound is refused
// (UsageError with the bound in the message) unless `allow_unstable`.
TimeStep choose_time_step(const mesh::CellMesh& mesh, const Material& material, const Physics& physics,
                          dynamics::IntegratorKind kind, double dt_requested, double safety, bool allow_unstable);

}  // namespace frac::dem
