#include "dem/beams.hpp"

#include <algorithm>

#include "core/parallel.hpp"
#include "core/vector_kernel.hpp"

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
  as_team(active_.size() > kMinParallelItems || n_ > kMinParallelItems, [&] {
    beam_pass(q);
#pragma omp barrier
    gather(f, add);
  });
}

namespace {
// One block of beams for each_response: their inputs gathered into arrays, so that the branch-free formula
// runs as a vector loop with no indirect load, and its outputs (a block fits in the first-level cache).
constexpr std::size_t kResponseBlock = 128;
struct ResponseBlock {
  alignas(64) double dx[kResponseBlock], dy[kResponseBlock], phi_i[kResponseBlock], phi_j[kResponseBlock];
  alignas(64) double e0x[kResponseBlock], e0y[kResponseBlock], l0[kResponseBlock];
  alignas(64) double alpha[kResponseBlock], beta[kResponseBlock], delta[kResponseBlock];
  alignas(64) double fx[kResponseBlock], fy[kResponseBlock], torque_i[kResponseBlock], torque_j[kResponseBlock];
  alignas(64) double energy[kResponseBlock], strain[kResponseBlock];
  alignas(64) double near[kResponseBlock];  // 1: the formula applies (a double: a vector loop stores it as such)
};

// beam_response_near_reference over the first `count` beams of the block, storing only part P (what is not
// stored, the compiler leaves out: the strain's division, the energy's products).
template <BeamResponsePart P>
FRACTURE_VECTOR_KERNEL void respond_near_reference(ResponseBlock& blk, std::size_t count) {
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    BeamResponse r;
    const bool near = beam_response_near_reference(blk.dx[k], blk.dy[k], blk.e0x[k], blk.e0y[k], blk.phi_i[k],
                                                   blk.phi_j[k], blk.l0[k], {blk.alpha[k], blk.beta[k], blk.delta[k]}, r);
    if constexpr (P == BeamResponsePart::forces) {
      blk.fx[k] = r.fx;
      blk.fy[k] = r.fy;
      blk.torque_i[k] = r.torque_i;
      blk.torque_j[k] = r.torque_j;
    } else if constexpr (P == BeamResponsePart::energy) {
      blk.energy[k] = r.energy;
    } else {
      blk.strain[k] = r.strain;
    }
    blk.near[k] = near ? 1.0 : 0.0;
  }
}

// breaking_bound_holds over the first `count` beams of the block, into `near` (1: the beam holds for sure).
FRACTURE_VECTOR_KERNEL void bound_breaking(ResponseBlock& blk, std::size_t count, double t_eps, double t_theta) {
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    const bool holds = breaking_bound_holds(blk.dx[k], blk.dy[k], blk.e0x[k], blk.e0y[k], blk.phi_i[k], blk.phi_j[k],
                                            blk.l0[k], t_eps, t_theta);
    blk.near[k] = holds ? 1.0 : 0.0;
  }
}
}  // namespace

template <class BeamOf, class OnBlock>
void Beams::each_block(std::span<const double> q, std::size_t first, std::size_t last, BeamOf&& beam_of,
                       OnBlock&& on_block) const {
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  const std::int32_t *cell_i = i_.data(), *cell_j = j_.data();
  const double *e0x = e0x_.data(), *e0y = e0y_.data(), *l0 = l0_.data();
  const BeamStiffness* stiffness = k_.data();
  ResponseBlock blk;
  for (std::size_t start = first; start < last; start += kResponseBlock) {
    const std::size_t count = std::min(kResponseBlock, last - start);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t b = beam_of(start + k);
      const auto i = static_cast<std::size_t>(cell_i[b]), j = static_cast<std::size_t>(cell_j[b]);
      blk.dx[k] = x[j] - x[i];
      blk.dy[k] = y[j] - y[i];
      blk.phi_i[k] = phi[i];
      blk.phi_j[k] = phi[j];
      blk.e0x[k] = e0x[b];
      blk.e0y[k] = e0y[b];
      blk.l0[k] = l0[b];
      blk.alpha[k] = stiffness[b].alpha;
      blk.beta[k] = stiffness[b].beta;
      blk.delta[k] = stiffness[b].delta;
    }
    on_block(start, count, blk);
  }
}

template <BeamResponsePart P, class BeamOf, class Use>
void Beams::each_response(std::span<const double> q, std::size_t first, std::size_t last, BeamOf&& beam_of,
                          Use&& use) const {
  each_block(q, first, last, beam_of, [&](std::size_t start, std::size_t count, ResponseBlock& blk) {
    respond_near_reference<P>(blk, count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t b = beam_of(start + k);
      if (blk.near[k] != 0.0) {
        BeamResponse r{};
        if constexpr (P == BeamResponsePart::forces) {
          r.fx = blk.fx[k];
          r.fy = blk.fy[k];
          r.torque_i = blk.torque_i[k];
          r.torque_j = blk.torque_j[k];
        } else if constexpr (P == BeamResponsePart::energy) {
          r.energy = blk.energy[k];
        } else {
          r.strain = blk.strain[k];
        }
        use(start + k, b, r);
      } else {
        use(start + k, b, response(b, q));
      }
    }
  });
}

void Beams::beam_pass(std::span<const double> q) const {
  // Forces in parallel (each beam its own slot); each cell then gathers its intact beams in beam order (gather):
  // the same bits whatever the thread count.
  const std::int32_t* active = active_.data();
  BeamForce* out = force_.data();
  const Range mine = this_thread_range(active_.size());
  each_response<BeamResponsePart::forces>(
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
  const std::int32_t* active = active_.data();
  double* energy = energy_.data();
  double* part = energy_blocks_.data();
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    each_response<BeamResponsePart::energy>(
        q, mine.first, mine.last, [&](std::size_t k) { return static_cast<std::size_t>(active[k]); },
        [&](std::size_t k, std::size_t, const BeamResponse& r) { energy[k] = r.energy; });
#pragma omp barrier
    block_sums(energy, count, kBlock, mine, part);
  });
  return sum_of_blocks(part, count, kBlock);
}

void Beams::strains(std::span<const double> q, std::span<double> out) const {
  const std::size_t count = size();
  double* strain = out.data();
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    each_response<BeamResponsePart::strain>(
        q, mine.first, mine.last, [](std::size_t k) { return k; },
        [&](std::size_t, std::size_t b, const BeamResponse& r) { strain[b] = r.strain; });
  });
}

void Beams::break_beams(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken) {
  const std::size_t count = active_.size();
  if (verdict_.size() < count) verdict_.resize(count);
  // The verdicts in parallel (each beam its own slot; in blocks, the bound that clears most beams as a vector
  // loop, then the exact rule for the others), then the active list compacted in order: the same bits whatever
  // the thread count.
  Verdict* verdict = verdict_.data();
  const std::int32_t* active = active_.data();
  bool any = false;
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    bool mine_any = false;
    each_block(
        q, mine.first, mine.last, [&](std::size_t k) { return static_cast<std::size_t>(active[k]); },
        [&](std::size_t start, std::size_t n, ResponseBlock& blk) {
          bound_breaking(blk, n, t_eps, t_theta);
          for (std::size_t k = 0; k < n; ++k) {
            Verdict& v = verdict[start + k];
            v.mode = 0;
            if (blk.near[k] != 0.0) continue;
            const auto b = static_cast<std::size_t>(active[start + k]);
            v.mode = breaking_mode(blk.dx[k], blk.dy[k], blk.e0x[k], blk.e0y[k], blk.phi_i[k], blk.phi_j[k],
                                   blk.l0[k], k_[b], t_eps, t_theta, v.energy);
            mine_any = mine_any || v.mode != 0;
          }
        });
    if (mine_any) {
#pragma omp atomic write
      any = true;
    }
  });
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
