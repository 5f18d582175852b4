#include "dem/beams.hpp"

#include <algorithm>

namespace frac::dem {

Beams::Beams(const mesh::CellMesh& mesh, const Material& m) : n_(mesh.cells()) {
  const std::size_t nb = mesh.beams();
  i_.resize(nb);
  j_.resize(nb);
  l0_.resize(nb);
  e0x_.resize(nb);
  e0y_.resize(nb);
  k_.resize(nb);
  intact_.assign(nb, 1);
  active_.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    i_[b] = static_cast<std::int32_t>(mesh.beam[b][0]);
    j_[b] = static_cast<std::int32_t>(mesh.beam[b][1]);
    const auto d = mesh.centroid[static_cast<std::size_t>(j_[b])] - mesh.centroid[static_cast<std::size_t>(i_[b])];
    // l0 from the centroids (the initial, force-free state), not from the stored length, so that the
    // reference state is exactly unstressed.
    l0_[b] = d.norm();
    e0x_[b] = d.x() / l0_[b];
    e0y_[b] = d.y() / l0_[b];
    k_[b] = beam_stiffness(l0_[b], mesh.beam_section[b], m.thickness, m.beam_modulus, m.shear_ratio);
    active_[b] = static_cast<std::int32_t>(b);
  }
}

BeamResponse Beams::response(std::size_t b, std::span<const double> q) const {
  const auto i = static_cast<std::size_t>(i_[b]), j = static_cast<std::size_t>(j_[b]);
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  return beam_response(x[j] - x[i], y[j] - y[i], e0x_[b], e0y_[b], phi[i], phi[j], l0_[b], k_[b]);
}

void Beams::add_forces(std::span<const double> q, std::span<double> f) const {
  double* fx = f.data();
  double* fy = fx + n_;
  double* tz = fy + n_;
  const std::size_t count = active_.size();
  if (response_.size() < count) response_.resize(count);
  // Responses in parallel (each beam its own slot), then the forces summed in beam order: the same
  // bits whatever the thread count.
#pragma omp parallel for schedule(static) if (count > 4096)
  for (std::size_t k = 0; k < count; ++k) response_[k] = response(static_cast<std::size_t>(active_[k]), q);
  for (std::size_t k = 0; k < count; ++k) {
    const BeamResponse& r = response_[k];
    const auto b = static_cast<std::size_t>(active_[k]);
    const auto i = static_cast<std::size_t>(i_[b]), j = static_cast<std::size_t>(j_[b]);
    fx[i] += r.fx;
    fy[i] += r.fy;
    fx[j] -= r.fx;
    fy[j] -= r.fy;
    tz[i] += r.torque_i;
    tz[j] += r.torque_j;
  }
}

double Beams::energy(std::span<const double> q) const {
  double e = 0;
  for (const std::int32_t b : active_) e += response(static_cast<std::size_t>(b), q).energy;
  return e;
}

void Beams::strains(std::span<const double> q, std::span<double> out) const {
  for (std::size_t b = 0; b < size(); ++b) out[b] = response(b, q).strain;
}

void Beams::break_beams(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const auto b = static_cast<std::size_t>(active_[k]);
    const BeamResponse r = response(b, q);
    const int mode = breaking_mode(r.strain, r.theta_i, r.theta_j, t_eps, t_theta);
    if (mode == 0) {
      active_[kept++] = active_[k];
    } else {
      intact_[b] = 0;
      broken.push_back({static_cast<std::int64_t>(b), mode, r.energy});
    }
  }
  active_.resize(kept);
}

void Beams::remove(std::size_t b) {
  if (!intact_[b]) return;
  intact_[b] = 0;
  active_.erase(std::find(active_.begin(), active_.end(), static_cast<std::int32_t>(b)));
}

void Beams::remove_all() {
  std::fill(intact_.begin(), intact_.end(), std::uint8_t{0});
  active_.clear();
}

}  // namespace frac::dem
