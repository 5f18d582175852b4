#include "dem/beams.hpp"

#include <algorithm>

#include "core/parallel.hpp"

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
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  double* fx = f.data();
  double* fy = fx + n_;
  double* tz = fy + n_;
  const std::size_t count = active_.size();
  if (force_.size() < count) {
    force_.resize(count);
    far_.resize(count);
  }
  // Forces in parallel (each beam its own slot), then summed in beam order: the same bits whatever the
  // thread count. First the branch-free formula of a beam near its reference orientation (no library
  // call, no unpredictable branch; GCC vectorises it where the target has gathers, e.g. -mavx2); then the
  // beams it does not cover (rotated by more than π/8), one at a time.
  const std::int32_t* active = active_.data();
  const std::int32_t *cell_i = i_.data(), *cell_j = j_.data();
  const double *e0x = e0x_.data(), *e0y = e0y_.data(), *l0 = l0_.data();
  const BeamStiffness* stiffness = k_.data();
  BeamForce* out = force_.data();
  std::uint8_t* far = far_.data();
#pragma omp parallel for simd schedule(static) if (count > kMinParallelItems)
  for (std::size_t k = 0; k < count; ++k) {
    const auto b = static_cast<std::size_t>(active[k]);
    const auto i = static_cast<std::size_t>(cell_i[b]), j = static_cast<std::size_t>(cell_j[b]);
    BeamResponse r;
    const bool near =
        beam_response_near_reference(x[j] - x[i], y[j] - y[i], e0x[b], e0y[b], phi[i], phi[j], l0[b], stiffness[b], r);
    out[k] = {r.fx, r.fy, r.torque_i, r.torque_j};
    far[k] = !near;
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (far[k]) {
      const BeamResponse r = response(static_cast<std::size_t>(active_[k]), q);
      out[k] = {r.fx, r.fy, r.torque_i, r.torque_j};
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    const BeamForce& r = force_[k];
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
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  const std::size_t count = active_.size();
  if (verdict_.size() < count) verdict_.resize(count);
  // The verdicts in parallel (each beam its own slot), then the active list compacted in order: the same
  // bits whatever the thread count.
  Verdict* verdict = verdict_.data();
#pragma omp parallel for schedule(static) if (count > kMinParallelItems)
  for (std::size_t k = 0; k < count; ++k) {
    const auto b = static_cast<std::size_t>(active_[k]);
    const auto i = static_cast<std::size_t>(i_[b]), j = static_cast<std::size_t>(j_[b]);
    verdict[k].mode = breaking_mode(x[j] - x[i], y[j] - y[i], e0x_[b], e0y_[b], phi[i], phi[j], l0_[b], k_[b], t_eps,
                                    t_theta, verdict[k].energy);
  }
  std::size_t kept = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const auto b = static_cast<std::size_t>(active_[k]);
    if (verdict[k].mode == 0) {
      active_[kept++] = active_[k];
    } else {
      intact_[b] = 0;
      broken.push_back({static_cast<std::int64_t>(b), verdict[k].mode, verdict[k].energy});
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
