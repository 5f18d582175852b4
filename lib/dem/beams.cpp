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
  index_cells();
  force_.resize(nb);
}

void Beams::index_cells() {
  cell_start_.assign(n_ + 1, 0);
  for (const std::int32_t b : active_) {
    ++cell_start_[static_cast<std::size_t>(i_[static_cast<std::size_t>(b)]) + 1];
    ++cell_start_[static_cast<std::size_t>(j_[static_cast<std::size_t>(b)]) + 1];
  }
  for (std::size_t c = 0; c < n_; ++c) cell_start_[c + 1] += cell_start_[c];
  beams_of_.resize(2 * active_.size());
  cell_count_.assign(n_, 0);
  for (const std::int32_t b : active_) {
    const auto i = static_cast<std::size_t>(i_[static_cast<std::size_t>(b)]);
    const auto j = static_cast<std::size_t>(j_[static_cast<std::size_t>(b)]);
    beams_of_[static_cast<std::size_t>(cell_start_[i] + cell_count_[i]++)] = {b, 0, 1.0};
    beams_of_[static_cast<std::size_t>(cell_start_[j] + cell_count_[j]++)] = {b, 1, -1.0};
  }
}

void Beams::unindex(std::size_t b) {
  for (const std::int32_t c : {i_[b], j_[b]}) {
    CellBeam* first = beams_of_.data() + cell_start_[static_cast<std::size_t>(c)];
    CellBeam* last = first + cell_count_[static_cast<std::size_t>(c)];
    CellBeam* hit = std::find_if(first, last, [b](const CellBeam& e) { return e.beam == static_cast<std::int32_t>(b); });
    if (hit == last) continue;  // not listed (cannot happen for an intact beam)
    std::copy(hit + 1, last, hit);  // the others keep their order
    --cell_count_[static_cast<std::size_t>(c)];
  }
}

BeamResponse Beams::response(std::size_t b, std::span<const double> q) const {
  const auto i = static_cast<std::size_t>(i_[b]), j = static_cast<std::size_t>(j_[b]);
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  return beam_response(x[j] - x[i], y[j] - y[i], e0x_[b], e0y_[b], phi[i], phi[j], l0_[b], k_[b]);
}

void Beams::add_forces(std::span<const double> q, std::span<double> f) const { forces(q, f, true); }

void Beams::set_forces(std::span<const double> q, std::span<double> f) const { forces(q, f, false); }

void Beams::forces(std::span<const double> q, std::span<double> f, bool add) const {
  reserve();
  as_team(active_.size() > kMinParallelItems || n_ > kMinParallelItems, [&] {
    beam_pass(q);
#pragma omp barrier
    gather(f, add);
  });
}

void Beams::reserve() const {
  if (far_.size() < active_.size()) far_.resize(active_.size());
}

template <class BeamOf, class Use>
void Beams::each_response(std::span<const double> q, std::size_t first, std::size_t last, BeamOf&& beam_of,
                          Use&& use) const {
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  const std::int32_t *cell_i = i_.data(), *cell_j = j_.data();
  const double *e0x = e0x_.data(), *e0y = e0y_.data(), *l0 = l0_.data();
  const BeamStiffness* stiffness = k_.data();
  std::uint8_t* far = far_.data();
#pragma omp simd
  for (std::size_t k = first; k < last; ++k) {
    const std::size_t b = beam_of(k);
    const auto i = static_cast<std::size_t>(cell_i[b]), j = static_cast<std::size_t>(cell_j[b]);
    BeamResponse r;
    const bool near = beam_response_near_reference(x[j] - x[i], y[j] - y[i], e0x[b], e0y[b], phi[i], phi[j], l0[b],
                                                   stiffness[b], r);
    use(k, b, r);
    far[k] = !near;
  }
  for (std::size_t k = first; k < last; ++k) {
    if (far[k]) {
      const std::size_t b = beam_of(k);
      use(k, b, response(b, q));
    }
  }
}

void Beams::beam_pass(std::span<const double> q) const {
  // Forces in parallel (each beam its own slot); each cell then gathers its intact beams in beam order (gather):
  // the same bits whatever the thread count.
  const std::int32_t* active = active_.data();
  BeamForce* out = force_.data();
  const Range mine = this_thread_range(active_.size());
  each_response(
      q, mine.first, mine.last, [&](std::size_t k) { return static_cast<std::size_t>(active[k]); },
      [&](std::size_t, std::size_t b, const BeamResponse& r) { out[b] = {r.fx, r.fy, {r.torque_i, r.torque_j}}; });
}

void Beams::gather(std::span<double> f, bool add) const {
  double* fx = f.data();
  double* fy = fx + n_;
  double* tz = fy + n_;
  // On cell i the beam adds (F, τ_i), on cell j (−F, τ_j) (as + (−1)·F: the same bits as − F), in beam
  // order, as a loop over the beams would; onto f, or onto zero (the same bits as onto zeros).
  const std::int32_t* start = cell_start_.data();
  const std::int32_t* beams_in = cell_count_.data();
  const CellBeam* beams_of = beams_of_.data();
  const BeamForce* out = force_.data();
  const Range mine = this_thread_range(n_);
  for (std::size_t c = mine.first; c < mine.last; ++c) {
    double sx = add ? fx[c] : 0.0, sy = add ? fy[c] : 0.0, st = add ? tz[c] : 0.0;
    for (auto s = start[c]; s < start[c] + beams_in[c]; ++s) {
      const CellBeam cb = beams_of[s];
      const BeamForce& r = out[static_cast<std::size_t>(cb.beam)];
      sx += cb.sign * r.fx;
      sy += cb.sign * r.fy;
      st += r.torque[cb.end];
    }
    fx[c] = sx;
    fy[c] = sy;
    tz[c] = st;
  }
}

double Beams::energy(std::span<const double> q) const {
  // Each beam's energy in parallel, in its own slot; then sums over fixed blocks of beams (each by the thread
  // whose part the block starts in), added up in block order: the same bits whatever the thread count.
  constexpr std::size_t kBlock = 256;
  const std::size_t count = active_.size(), blocks = (count + kBlock - 1) / kBlock;
  if (energy_.size() < count) energy_.resize(count);
  energy_blocks_.resize(blocks);
  reserve();
  const std::int32_t* active = active_.data();
  double* energy = energy_.data();
  double* part = energy_blocks_.data();
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    each_response(
        q, mine.first, mine.last, [&](std::size_t k) { return static_cast<std::size_t>(active[k]); },
        [&](std::size_t k, std::size_t, const BeamResponse& r) { energy[k] = r.energy; });
#pragma omp barrier
    block_sums(energy, count, kBlock, mine, part);
  });
  return sum_of_blocks(part, count, kBlock);
}

void Beams::strains(std::span<const double> q, std::span<double> out) const {
  const std::size_t count = size();
  if (far_.size() < count) far_.resize(count);
  double* strain = out.data();
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    each_response(
        q, mine.first, mine.last, [](std::size_t k) { return k; },
        [&](std::size_t, std::size_t b, const BeamResponse& r) { strain[b] = r.strain; });
  });
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
  bool any = false;
#pragma omp parallel for schedule(static) if (count > kMinParallelItems) reduction(|| : any)
  for (std::size_t k = 0; k < count; ++k) {
    const auto b = static_cast<std::size_t>(active_[k]);
    const auto i = static_cast<std::size_t>(i_[b]), j = static_cast<std::size_t>(j_[b]);
    verdict[k].mode = breaking_mode(x[j] - x[i], y[j] - y[i], e0x_[b], e0y_[b], phi[i], phi[j], l0_[b], k_[b], t_eps,
                                    t_theta, verdict[k].energy);
    any = any || verdict[k].mode != 0;
  }
  if (!any) return;  // most steps: nothing broke, the list stays as it is
  std::size_t kept = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const auto b = static_cast<std::size_t>(active_[k]);
    if (verdict[k].mode == 0) {
      active_[kept++] = active_[k];
    } else {
      intact_[b] = 0;
      unindex(b);
      broken.push_back({static_cast<std::int64_t>(b), verdict[k].mode, verdict[k].energy});
    }
  }
  active_.resize(kept);
}

void Beams::remove(std::size_t b) {
  if (!intact_[b]) return;
  intact_[b] = 0;
  active_.erase(std::find(active_.begin(), active_.end(), static_cast<std::int32_t>(b)));
  unindex(b);
}

void Beams::remove_all() {
  std::fill(intact_.begin(), intact_.end(), std::uint8_t{0});
  active_.clear();
  index_cells();
}

}  // namespace frac::dem
