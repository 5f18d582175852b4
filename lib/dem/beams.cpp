#include "dem/beams.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/vector_kernel.hpp"

namespace frac::dem {

void Beams::BeamTable::resize(std::size_t n) {
  for (auto* v : {&beam, &i, &j}) v->resize(n);
  for (auto* v : {&e0x, &e0y, &l0, &alpha, &beta, &delta}) v->resize(n);
}

void Beams::BeamTable::copy_entry(std::size_t to, const BeamTable& source, std::size_t from) {
  beam[to] = source.beam[from];
  i[to] = source.i[from];
  j[to] = source.j[from];
  e0x[to] = source.e0x[from];
  e0y[to] = source.e0y[from];
  l0[to] = source.l0[from];
  alpha[to] = source.alpha[from];
  beta[to] = source.beta[from];
  delta[to] = source.delta[from];
}

void Beams::BeamTable::erase(std::size_t k) {
  for (std::size_t e = k; e + 1 < size(); ++e) copy_entry(e, *this, e + 1);
  resize(size() - 1);
}

void Beams::BeamTable::push_back(const BeamTable& source, std::size_t from) {
  resize(size() + 1);
  copy_entry(size() - 1, source, from);
}

template <class Keep>
Beams::BeamTable Beams::BeamTable::merged(const BeamTable& a, const BeamTable& b, Keep&& in) {
  BeamTable out;
  std::size_t ka = 0, kb = 0, count = b.size();
  for (std::size_t k = 0; k < a.size(); ++k) count += in(a, k) ? 1 : 0;
  out.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    while (ka < a.size() && !in(a, ka)) ++ka;
    if (kb == b.size() || (ka < a.size() && a.beam[ka] < b.beam[kb])) {
      out.copy_entry(k, a, ka++);
    } else {
      out.copy_entry(k, b, kb++);
    }
  }
  return out;
}

Beams::Beams(const mesh::CellMesh& mesh, const Material& m) : n_(mesh.cells()) {
  const std::size_t nb = mesh.beams();
  BeamTable& all = active_;  // (every beam intact)
  all.resize(nb);
  intact_.assign(nb, 1);
  for (std::size_t b = 0; b < nb; ++b) {
    all.beam[b] = static_cast<std::int32_t>(b);
    all.i[b] = static_cast<std::int32_t>(mesh.beam[b][0]);
    all.j[b] = static_cast<std::int32_t>(mesh.beam[b][1]);
    const auto i = static_cast<std::size_t>(all.i[b]), j = static_cast<std::size_t>(all.j[b]);
    const auto d = mesh.centroid[j] - mesh.centroid[i];
    // l0 from the centroids (the initial, force-free state), not from the stored length, so that the
    // reference state is exactly unstressed.
    const double l0 = d.norm();
    all.l0[b] = l0;
    all.e0x[b] = d.x() / l0;
    all.e0y[b] = d.y() / l0;
    const BeamStiffness k = beam_stiffness(l0, mesh.beam_section[b], m.thickness, m.beam_modulus, m.shear_ratio);
    all.alpha[b] = k.alpha;
    all.beta[b] = k.beta;
    all.delta[b] = k.delta;
  }
  index_cells();
  force_.resize(nb);
}

void Beams::index_cells() {
  cell_start_.assign(n_ + 1, 0);
  for (std::size_t k = 0; k < active_.size(); ++k) {
    ++cell_start_[static_cast<std::size_t>(active_.i[k]) + 1];
    ++cell_start_[static_cast<std::size_t>(active_.j[k]) + 1];
  }
  for (std::size_t c = 0; c < n_; ++c) cell_start_[c + 1] += cell_start_[c];
  beams_of_.resize(2 * active_.size());
  cell_count_.assign(n_, 0);
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const std::int32_t b = active_.beam[k];
    const auto i = static_cast<std::size_t>(active_.i[k]);
    const auto j = static_cast<std::size_t>(active_.j[k]);
    beams_of_[static_cast<std::size_t>(cell_start_[i] + cell_count_[i]++)] = {b, 0};
    beams_of_[static_cast<std::size_t>(cell_start_[j] + cell_count_[j]++)] = {b, 1};
  }
}

Beams::Entry Beams::find(std::size_t b) const {
  for (const BeamTable* t : {&active_, &retired_}) {
    const auto hit = std::lower_bound(t->beam.begin(), t->beam.end(), static_cast<std::int32_t>(b));
    if (hit != t->beam.end() && *hit == static_cast<std::int32_t>(b))
      return {t, static_cast<std::size_t>(hit - t->beam.begin())};
  }
  throw RuntimeError("beams: no beam " + std::to_string(b));
}

void Beams::unindex(const BeamTable& t, std::size_t k) {
  const std::int32_t b = t.beam[k];
  for (const std::int32_t c : {t.i[k], t.j[k]}) {
    CellBeam* first = beams_of_.data() + cell_start_[static_cast<std::size_t>(c)];
    CellBeam* last = first + cell_count_[static_cast<std::size_t>(c)];
    CellBeam* hit = std::find_if(first, last, [b](const CellBeam& e) { return e.beam == b; });
    if (hit == last) continue;      // not listed (cannot happen for an intact beam)
    std::copy(hit + 1, last, hit);  // the others keep their order
    --cell_count_[static_cast<std::size_t>(c)];
  }
}

BeamResponse Beams::response(const BeamTable& t, std::size_t k, std::span<const double> q) const {
  const auto i = static_cast<std::size_t>(t.i[k]), j = static_cast<std::size_t>(t.j[k]);
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  return beam_response(x[j] - x[i], y[j] - y[i], t.e0x[k], t.e0y[k], phi[i], phi[j], t.l0[k], Entry{&t, k}.stiffness());
}

void Beams::add_forces(std::span<const double> q, std::span<double> f) const { forces(q, f, true); }

void Beams::set_forces(std::span<const double> q, std::span<double> f) const { forces(q, f, false); }

void Beams::forces(std::span<const double> q, std::span<double> f, bool add) const {
  as_team(active_.size() > kMinParallelItems || n_ > kMinParallelItems, [&] {
    const auto t = static_cast<std::size_t>(thread_index()), nt = static_cast<std::size_t>(thread_count());
    beam_pass(q, t, nt);
    team_barrier();
    gather(f, add, t, nt);
  });
}

namespace {
// One block of beams for each_response: their states gathered into arrays, so that the branch-free formula runs
// as a vector loop with no indirect load (the constants are read in sequence from the beam table), and its
// outputs (a block fits in the first-level cache).
constexpr std::size_t kResponseBlock = 128;
struct ResponseBlock {
  alignas(64) double dx[kResponseBlock], dy[kResponseBlock], phi_i[kResponseBlock], phi_j[kResponseBlock];
  const double *e0x, *e0y, *l0, *alpha, *beta, *delta;  // the block's entries of the table
  alignas(64) double fx[kResponseBlock], fy[kResponseBlock], torque_i[kResponseBlock], torque_j[kResponseBlock];
  alignas(64) double energy[kResponseBlock], strain[kResponseBlock];
  alignas(64) double near[kResponseBlock];  // 1: the formula applies (a double: a vector loop stores it as such)
};

// beam_response_near_reference over the first `count` beams of a block, storing only part P (what is not
// stored, the compiler leaves out: the strain's division, the energy's products) into `out`, and whether the
// formula applies into `near`.
template <BeamResponsePart P>
FRACTURE_VECTOR_KERNEL void respond_near_reference(std::size_t count, const double* __restrict dx,
                                                   const double* __restrict dy, const double* __restrict phi_i,
                                                   const double* __restrict phi_j, const double* __restrict e0x,
                                                   const double* __restrict e0y, const double* __restrict l0,
                                                   const double* __restrict alpha, const double* __restrict beta,
                                                   const double* __restrict delta, double* __restrict out0,
                                                   double* __restrict out1, double* __restrict out2,
                                                   double* __restrict out3, double* __restrict near) {
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    BeamResponse r;
    const bool applies = beam_response_near_reference(dx[k], dy[k], e0x[k], e0y[k], phi_i[k], phi_j[k], l0[k],
                                                      {alpha[k], beta[k], delta[k]}, r);
    if constexpr (P == BeamResponsePart::forces) {
      out0[k] = r.fx;
      out1[k] = r.fy;
      out2[k] = r.torque_i;
      out3[k] = r.torque_j;
    } else if constexpr (P == BeamResponsePart::energy) {
      out0[k] = r.energy;
    } else {
      out0[k] = r.strain;
    }
    near[k] = applies ? 1.0 : 0.0;
  }
}

// respond_near_reference on a block's arrays, part P into its own output arrays.
template <BeamResponsePart P>
void respond_block(ResponseBlock& blk, std::size_t count) {
  double* out0 = P == BeamResponsePart::forces ? blk.fx : P == BeamResponsePart::energy ? blk.energy : blk.strain;
  respond_near_reference<P>(count, blk.dx, blk.dy, blk.phi_i, blk.phi_j, blk.e0x, blk.e0y, blk.l0, blk.alpha, blk.beta,
                            blk.delta, out0, blk.fy, blk.torque_i, blk.torque_j, blk.near);
}

// breaking_bound_holds over the first `count` beams of a block, into `holds` (1: the beam holds for sure).
FRACTURE_VECTOR_KERNEL void bound_breaking(std::size_t count, const double* __restrict dx, const double* __restrict dy,
                                           const double* __restrict phi_i, const double* __restrict phi_j,
                                           const double* __restrict e0x, const double* __restrict e0y,
                                           const double* __restrict l0, double t_eps, double t_theta,
                                           double* __restrict holds) {
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    const bool sure = breaking_bound_holds(dx[k], dy[k], e0x[k], e0y[k], phi_i[k], phi_j[k], l0[k], t_eps, t_theta);
    holds[k] = sure ? 1.0 : 0.0;
  }
}
}  // namespace

template <class OnBlock>
void Beams::each_block(std::span<const double> q, const BeamTable& t, std::size_t first, std::size_t last,
                       OnBlock&& on_block) const {
  const double* x = q.data();
  const double* y = x + n_;
  const double* phi = y + n_;
  const std::int32_t *cell_i = t.i.data(), *cell_j = t.j.data();
  ResponseBlock blk;
  for (std::size_t start = first; start < last; start += kResponseBlock) {
    const std::size_t count = std::min(kResponseBlock, last - start);
    for (std::size_t k = 0; k < count; ++k) {
      const auto i = static_cast<std::size_t>(cell_i[start + k]), j = static_cast<std::size_t>(cell_j[start + k]);
      blk.dx[k] = x[j] - x[i];
      blk.dy[k] = y[j] - y[i];
      blk.phi_i[k] = phi[i];
      blk.phi_j[k] = phi[j];
    }
    blk.e0x = t.e0x.data() + start;
    blk.e0y = t.e0y.data() + start;
    blk.l0 = t.l0.data() + start;
    blk.alpha = t.alpha.data() + start;
    blk.beta = t.beta.data() + start;
    blk.delta = t.delta.data() + start;
    on_block(start, count, blk);
  }
}

template <BeamResponsePart P, class Use>
void Beams::each_response(std::span<const double> q, const BeamTable& t, std::size_t first, std::size_t last, Use&& use,
                          bool broken_too) const {
  const bool some_broken = !broken_too && &t == &active_ && broken_in_active_ > 0;
  each_block(q, t, first, last, [&](std::size_t start, std::size_t count, ResponseBlock& blk) {
    respond_block<P>(blk, count);
    for (std::size_t k = 0; k < count; ++k) {
      const auto b = static_cast<std::size_t>(t.beam[start + k]);
      if (some_broken && intact_[b] == 0) {
        use(start + k, b, BeamResponse{});
      } else if (blk.near[k] != 0.0) {
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
        use(start + k, b, response(t, start + k, q));
      }
    }
  });
}

void Beams::beam_pass(std::span<const double> q, std::size_t t, std::size_t nt) const {
  // Forces in parallel (each beam its own slot); each cell then gathers its intact beams in beam order (gather):
  // the same bits whatever the thread count.
  BeamForce* out = force_.data();
  const Range mine = static_range(active_.size(), t, nt);
  each_response<BeamResponsePart::forces>(q, active_, mine.first, mine.last,
                                          [&](std::size_t, std::size_t b, const BeamResponse& r) {
                                            out[b] = {r.fx, r.fy, {r.torque_i, r.torque_j}};
                                          });
}

void Beams::gather(std::span<double> f, bool add, std::size_t t, std::size_t nt) const {
  double* fx = f.data();
  double* fy = fx + n_;
  double* tz = fy + n_;
  // On cell i the beam adds (F, τ_i), on cell j (−F, τ_j) (as + (−1)·F: the same bits as − F), in beam
  // order, as a loop over the beams would; onto f, or onto zero (the same bits as onto zeros).
  const std::int32_t* start = cell_start_.data();
  const std::int32_t* beams_in = cell_count_.data();
  const CellBeam* beams_of = beams_of_.data();
  const BeamForce* out = force_.data();
  const Range mine = static_range(n_, t, nt);
  for (std::size_t c = mine.first; c < mine.last; ++c) {
    double sx = add ? fx[c] : 0.0, sy = add ? fy[c] : 0.0, st = add ? tz[c] : 0.0;
    for (auto s = start[c]; s < start[c] + beams_in[c]; ++s) {
      const CellBeam cb = beams_of[s];
      const BeamForce& r = out[static_cast<std::size_t>(cb.beam)];
      const double sign = 1 - 2 * cb.end;  // (exact: +1 or −1)
      sx += sign * r.fx;
      sy += sign * r.fy;
      st += r.torque[cb.end];
    }
    fx[c] = sx;
    fy[c] = sy;
    tz[c] = st;
  }
}

double Beams::energy(std::span<const double> q) const {
  // Exact sums (core/exact_sum) of each thread's beams, merged: the same value whatever the thread count or the
  // beams' order.
  const std::size_t count = active_.size();
  energy_parts_.assign(static_cast<std::size_t>(max_threads()), ExactSum{});
  as_team(count > kMinParallelItems, [&] {
    const Range mine = this_thread_range(count);
    ExactSum& sum = energy_parts_[static_cast<std::size_t>(thread_index())];
    each_response<BeamResponsePart::energy>(
        q, active_, mine.first, mine.last, [&](std::size_t, std::size_t, const BeamResponse& r) { sum.add(r.energy); });
  });
  return sum_of(energy_parts_);
}

void Beams::strains(std::span<const double> q, std::span<double> out) const {
  double* strain = out.data();
  as_team(size() > kMinParallelItems, [&] {
    for (const BeamTable* t : {&active_, &retired_}) {
      const Range mine = this_thread_range(t->size());
      each_response<BeamResponsePart::strain>(
          q, *t, mine.first, mine.last,
          [&](std::size_t, std::size_t b, const BeamResponse& r) { strain[b] = r.strain; }, true);
    }
  });
}

void Beams::break_beams(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken) {
  bind_breaking(q, t_eps, t_theta, broken);
  breaking_phases().run(team_size(active_.size() > kMinParallelItems));
}

void Beams::bind_breaking(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken) {
  breaking_state_ = {q, t_eps, t_theta, &broken};
  breaking_.reserve(static_cast<std::size_t>(max_threads()));  // (each thread's list grows with the beams it finds)
}

Phases Beams::breaking_phases() {
  Phases p;
  p.add({"beams: breaking verdicts", false, [this](std::size_t t, std::size_t nt) { find_breaks(t, nt); }, {}});
  p.add({"beams: break", true, [this](std::size_t, std::size_t nt) { apply_breaks(nt); }, {}});
  return p;
}

void Beams::find_breaks(std::size_t t, std::size_t nt) {
  // The verdicts in parallel (in blocks, the bound that clears most beams as a vector loop, then the exact rule
  // for the others), each thread listing the entries of its part that break; then (apply_breaks), in list
  // order, the beams marked broken: the same bits whatever the thread count.
  const std::span<const double> q = breaking_state_.q;
  const double t_eps = breaking_state_.t_eps, t_theta = breaking_state_.t_theta;
  const std::size_t count = active_.size();
  const Range mine = static_range(count, t, nt);
  std::vector<Breaking>& out = breaking_[t];
  out.clear();
  each_block(q, active_, mine.first, mine.last, [&](std::size_t start, std::size_t n, ResponseBlock& blk) {
    bound_breaking(n, blk.dx, blk.dy, blk.phi_i, blk.phi_j, blk.e0x, blk.e0y, blk.l0, t_eps, t_theta, blk.near);
    for (std::size_t k = 0; k < n; ++k) {
      if (blk.near[k] != 0.0) continue;  // holds for sure (breaking_bound_holds)
      const auto b = static_cast<std::size_t>(active_.beam[start + k]);
      if (intact_[b] == 0) continue;  // broke before, not yet out of the list
      Verdict v{0, 0.0};
      v.mode = exact_breaking_mode(blk.dx[k], blk.dy[k], blk.e0x[k], blk.e0y[k], blk.phi_i[k], blk.phi_j[k], blk.l0[k],
                                   Entry{&active_, start + k}.stiffness(), t_eps, t_theta, v.energy);
      if (v.mode != 0) out.push_back({start + k, v});
    }
  });
}

void Beams::apply_breaks(std::size_t nt) {
  std::vector<BeamBreak>& broken = *breaking_state_.broken;
  for (std::size_t t = 0; t < nt; ++t) {
    for (const Breaking& e : breaking_[t]) {
      const auto b = static_cast<std::size_t>(active_.beam[e.entry]);
      intact_[b] = 0;
      unindex(active_, e.entry);
      broken.push_back({static_cast<std::int64_t>(b), e.verdict.mode, e.verdict.energy});
      ++broken_in_active_;
    }
    breaking_[t].clear();
  }
  if (broken_in_active_ * kCompactEvery > active_.size()) compact_active();
}

void Beams::compact_active() {
  retired_ = BeamTable::merged(active_, retired_, [&](const BeamTable& t, std::size_t k) {
    return intact_[static_cast<std::size_t>(t.beam[k])] == 0;
  });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < active_.size(); ++k) {
    if (intact_[static_cast<std::size_t>(active_.beam[k])] == 0) continue;
    if (kept != k) active_.copy_entry(kept, active_, k);
    ++kept;
  }
  active_.resize(kept);
  broken_in_active_ = 0;
}

void Beams::remove(std::size_t b) {
  if (!intact_[b]) return;
  intact_[b] = 0;
  const std::size_t k = find(b).k;  // (an intact beam is in active_)
  unindex(active_, k);
  BeamTable one;
  one.push_back(active_, k);
  retired_ = BeamTable::merged(one, retired_, [](const BeamTable&, std::size_t) { return true; });
  active_.erase(k);
}

void Beams::remove_all() {
  std::fill(intact_.begin(), intact_.end(), std::uint8_t{0});
  retired_ = BeamTable::merged(active_, retired_, [](const BeamTable&, std::size_t) { return true; });
  active_ = BeamTable{};
  broken_in_active_ = 0;
  index_cells();
}

void Beams::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "beams");
  archive.array("intact", intact_, size());
  // The active list as it stands, broken beams not yet compacted out included: its blocks order the sums.
  std::vector<std::int32_t> active(active_.beam);
  archive.array("active", active);
  if (!archive.loading()) return;
  archive.require_below("active", active, size());
  std::size_t in_active = 0;
  for (std::size_t k = 0; k < active.size(); ++k) {
    if (k > 0 && active[k] <= active[k - 1]) archive.refuse("active", "not in beam order");
    if (intact_[static_cast<std::size_t>(active[k])] > 1) archive.refuse("intact", "holds a value other than 0 or 1");
    in_active += intact_[static_cast<std::size_t>(active[k])];
  }
  if (in_active != static_cast<std::size_t>(std::count(intact_.begin(), intact_.end(), std::uint8_t{1})))
    archive.refuse("active", "leaves out an intact beam");
  // Every beam in beam order, then split: those of the active list, and the others.
  const BeamTable all = BeamTable::merged(active_, retired_, [](const BeamTable&, std::size_t) { return true; });
  std::vector<std::uint8_t> listed(size(), 0);
  for (const std::int32_t b : active) listed[static_cast<std::size_t>(b)] = 1;
  const BeamTable none;
  active_ = BeamTable::merged(
      all, none, [&](const BeamTable& t, std::size_t k) { return listed[static_cast<std::size_t>(t.beam[k])] == 1; });
  retired_ = BeamTable::merged(
      all, none, [&](const BeamTable& t, std::size_t k) { return listed[static_cast<std::size_t>(t.beam[k])] == 0; });
  broken_in_active_ = active.size() - in_active;
  index_cells();
  for (std::size_t k = 0; k < active_.size(); ++k)
    if (!intact_[static_cast<std::size_t>(active_.beam[k])]) unindex(active_, k);
}

}  // namespace frac::dem
