#include "rubber/model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "rubber/failures.hpp"

namespace frac::rubber {
namespace {
// [begin, end) of `n` items for `worker` of `workers`, in contiguous blocks.
std::pair<std::size_t, std::size_t> worker_range(std::size_t n, std::size_t worker, std::size_t workers) {
  return {n * worker / workers, n * (worker + 1) / workers};
}
}  // namespace

Model::Model(Lattice lattice, ModelOptions options) : lattice_(std::move(lattice)), options_(std::move(options)) {
  const int threads = std::min(options_.threads <= 0 ? 0 : options_.threads, ForceContext::kMaxWorkers);
  threads_ = std::min(threads > 0 ? threads : static_cast<int>(processor_count()), ForceContext::kMaxWorkers);
  passes_ = select_passes(options_.law, options_.damping);

  const std::size_t n = lattice_.n, nb = lattice_.bonds();
  status_.assign(nb, kRemoved);
  for (std::size_t b = 0; b < nb; ++b)
    if (lattice_.exists[b] && lattice_.intact[b]) status_[b] = kIntact;
  past_.assign(nb, 0);
  cutoff_.assign(nb, options_.law.params.cutoff);
  bond_.assign(nb, BondData{0, 0, 0, 0, 0, 0});
  D_.assign(12 * (n + 1), 0.0);
  const std::size_t blocks = (n + ForceContext::kEnergyBlock - 1) / ForceContext::kEnergyBlock;
  blocks_.assign(4 * blocks, 0.0);
  scratch_a_.assign(2 * n, 0.0);
  zero_v_.assign(2 * n, 0.0);
  face_.assign(n, 0);
  bool periodic = false;
  for (double s : lattice_.shift) periodic = periodic || s != 0;
  if (periodic) shift_ = lattice_.shift;

  ctx_.n = n;
  ctx_.nbr = lattice_.nbr.data();
  ctx_.status = status_.data();
  ctx_.past_cutoff = past_.data();
  ctx_.cutoff = cutoff_.data();
  ctx_.shift = periodic ? shift_.data() : nullptr;
  ctx_.bond = bond_.data();
  ctx_.D = D_.data();
  ctx_.block_energy = blocks_.data();
  if (!options_.residual.empty() && options_.residual.size() != 36)
    throw UsageError("three-body residual: 36 values (6 x 6 slots) expected");
  ctx_.residual = options_.residual.empty() ? nullptr : options_.residual.data();
  ctx_.freeze = options_.failure == Failure::freeze;
  ctx_.break_extra = ctx_.freeze ? 0.0 : options_.break_extra;
  if (ctx_.freeze) frozen_.assign(n, 0.0);
  ctx_.frozen = frozen_.data();
  ctx_.beta = options_.beta;
  ctx_.damping_onset = options_.damping_onset;
  ctx_.inv_mass = 1 / options_.node_mass;

  // Row-by-row fusion needs rows of the index layout (index = row · nx + column) whose forward bonds
  // reach only the same row or the next (or wrap from the last row to the first).
  const auto nx = static_cast<std::size_t>(std::max<std::int64_t>(lattice_.nx, 0));
  const auto ny = static_cast<std::size_t>(std::max<std::int64_t>(lattice_.ny, 0));
  fused_ = options_.fused && nx > 0 && nx * ny == n;
  for (std::size_t i = 0; i < n && fused_; ++i)
    for (std::size_t s = 0; s < 3; ++s) {
      const auto j = static_cast<std::size_t>(lattice_.nbr[6 * i + s]);
      if (j >= n) continue;
      const std::size_t ri = i / nx, rj = j / nx;
      const bool ok = rj == ri || rj == ri + 1 || (lattice_.periodic_y && ri == ny - 1 && rj == 0);
      if (!ok) fused_ = false;
    }
  rows_ = ny;
  row_len_ = nx;
  make_phases();
}

std::pair<std::size_t, std::size_t> Model::rows_of(std::size_t worker, std::size_t workers) const {
  return worker_range(rows_, worker, workers);
}

Phase Model::bonds_phase() {
  return {"lattice: bonds",
          false,
          [this](std::size_t t, std::size_t nt) {
            const auto [i0, i1] = worker_range(lattice_.n, t, nt);
            passes_->bonds(ctx_, i0, i1, static_cast<int>(t));
          },
          {}};
}

Phase Model::centres_phase() {
  return {"lattice: centres",
          false,
          [this](std::size_t t, std::size_t nt) {
            const auto [i0, i1] = worker_range(lattice_.n, t, nt);
            passes_->centres(ctx_, i0, i1);
          },
          {}};
}

// The fused schedule, each thread owning the rows [r0, r1):
//   edge bonds: the bonds of its last row (the next thread's first row needs them; with periodic y the first
//      row needs the last row's);
//   rows: row by row, bonds(r) then centres(r) (which needs bonds of rows r and r − 1), then gather(r − 1)
//      (which needs D of rows r − 2 .. r) for the rows strictly inside the range;
//   edge gathers: gather of its first and last rows, whose neighbours' D other threads computed.
void Model::make_phases() {
  const std::size_t L = row_len_;
  if (fused_) {
    evaluation_.add({"lattice: edge bonds",
                     false,
                     [this, L](std::size_t t, std::size_t nt) {
                       const auto [r0, r1] = rows_of(t, nt);
                       if (r1 > r0) passes_->bonds(ctx_, (r1 - 1) * L, r1 * L, static_cast<int>(t));
                     },
                     {}});
    evaluation_.add({"lattice: rows",
                     false,
                     [this, L](std::size_t t, std::size_t nt) {
                       const auto [r0, r1] = rows_of(t, nt);
                       for (std::size_t r = r0; r < r1; ++r) {
                         if (r + 1 != r1) passes_->bonds(ctx_, r * L, (r + 1) * L, static_cast<int>(t));
                         passes_->centres(ctx_, r * L, (r + 1) * L);
                         if (r >= r0 + 2) passes_->gather(ctx_, (r - 1) * L, r * L, static_cast<int>(t));
                       }
                     },
                     {}});
    evaluation_.add({"lattice: edge gathers",
                     false,
                     [this, L](std::size_t t, std::size_t nt) {
                       const auto [r0, r1] = rows_of(t, nt);
                       if (r1 == r0) return;
                       passes_->gather(ctx_, r0 * L, (r0 + 1) * L, static_cast<int>(t));
                       if (r1 - 1 > r0) passes_->gather(ctx_, (r1 - 1) * L, r1 * L, static_cast<int>(t));
                     },
                     {}});
  } else {
    evaluation_.add(bonds_phase());
    evaluation_.add(centres_phase());
    evaluation_.add({"lattice: gather",
                     false,
                     [this](std::size_t t, std::size_t nt) {
                       const auto [i0, i1] = worker_range(lattice_.n, t, nt);
                       passes_->gather(ctx_, i0, i1, static_cast<int>(t));
                     },
                     {}});
  }
  accelerations_.add(evaluation_);
  // After the evaluation that froze them, the failed bonds are broken; and where the next step starts from, for
  // the failures in it to be frozen where they happened.
  if (ctx_.freeze)
    accelerations_.add({"lattice: failures settled",
                        false,
                        [this](std::size_t t, std::size_t nt) {
                          const auto [i0, i1] = worker_range(lattice_.n, t, nt);
                          settle_failures(ctx_, i0, i1);
                          const std::size_t n = lattice_.n;
                          std::copy(ctx_.x + i0, ctx_.x + i1, q_prev_.begin() + static_cast<std::ptrdiff_t>(i0));
                          std::copy(ctx_.y + i0, ctx_.y + i1, q_prev_.begin() + static_cast<std::ptrdiff_t>(n + i0));
                        },
                        {}});
  const auto blocks_of = [this](std::size_t t, std::size_t nt) { return worker_range(blocks_.size() / 4, t, nt); };
  energy_.add(bonds_phase());
  energy_.add({"lattice: energy",
               false,
               [this, blocks_of](std::size_t t, std::size_t nt) {
                 const auto [k0, k1] = blocks_of(t, nt);
                 passes_->energy(ctx_, k0, k1);
               },
               {}});
  virial_.add(bonds_phase());
  virial_.add(centres_phase());
  virial_.add({"lattice: virial",
               false,
               [this, blocks_of](std::size_t t, std::size_t nt) {
                 const auto [k0, k1] = blocks_of(t, nt);
                 virial_blocks(ctx_, k0, k1);
               },
               {}});
}

void Model::set_box(const Eigen::Matrix2d& F) {
  if (shift_.empty()) return;
  for (std::size_t b = 0; b < lattice_.bonds(); ++b) {
    const double sx = lattice_.shift[2 * b], sy = lattice_.shift[2 * b + 1];
    shift_[2 * b] = F(0, 0) * sx + F(0, 1) * sy;
    shift_[2 * b + 1] = F(1, 0) * sx + F(1, 1) * sy;
  }
}

void Model::remove_bond(std::size_t b) { status_.at(b) = kRemoved; }
void Model::set_cutoff(std::size_t b, double cutoff) { cutoff_.at(b) = cutoff; }

double Model::bond_length(std::size_t b, std::span<const double> q) const {
  const std::size_t n = lattice_.n, i = b / 3;
  const auto j = static_cast<std::size_t>(lattice_.nbr[6 * i + b % 3]);
  if (j >= n) return 0;
  double bx = q[j] - q[i], by = q[n + j] - q[n + i];
  if (!shift_.empty()) {
    bx += shift_[2 * b];
    by += shift_[2 * b + 1];
  }
  return std::sqrt(bx * bx + by * by);
}

bool Model::holds(std::size_t b, std::span<const double> q) const {
  return status_[b] == kIntact && bond_length(b, q) < cutoff_[b];
}

std::size_t Model::toughen(std::span<const double> q, double trigger, double cutoff) {
  const std::size_t n = lattice_.n;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t face = 0;
    for (std::size_t s = 0; s < 6; ++s) {
      const auto j = static_cast<std::size_t>(lattice_.nbr[6 * i + s]);
      if (j >= n) continue;  // a free edge, not a crack face
      const std::size_t b = s < 3 ? 3 * i + s : 3 * j + s - 3;
      face |= static_cast<std::uint8_t>(status_[b] != kIntact || past_[b] != 0);
    }
    face_[i] = face;
  }
  std::size_t raised = 0;
  for (std::size_t b = 0; b < 3 * n; ++b) {
    if (status_[b] != kIntact || cutoff_[b] >= cutoff) continue;
    const std::size_t i = b / 3, j = lattice_.bond_other(b);
    if (!(face_[i] || face_[j])) continue;
    if (bond_length(b, q) < trigger) {
      cutoff_[b] = cutoff;
      ++raised;
    }
  }
  return raised;
}

void Model::clamp(std::span<const std::size_t> nodes, std::span<const double> q) {
  const std::size_t n = lattice_.n;
  for (std::size_t i : nodes) {
    if (i >= n) throw UsageError("clamp: node " + std::to_string(i) + " out of range");
    clamped_.push_back(i);
  }
  std::sort(clamped_.begin(), clamped_.end());
  clamped_.erase(std::unique(clamped_.begin(), clamped_.end()), clamped_.end());
  prescribed_.clear();
  clamp_q_.clear();
  for (std::size_t i : clamped_) prescribed_.push_back(i);
  for (std::size_t i : clamped_) prescribed_.push_back(n + i);
  for (std::size_t k : prescribed_) clamp_q_.push_back(q[k]);
  clamp_v_.assign(prescribed_.size(), 0.0);
  clamp_until_ = 0;
}

void Model::clamp(std::span<const std::size_t> nodes, std::span<const double> q, std::span<const double> v,
                  double until) {
  clamp(nodes, q);
  for (std::size_t k = 0; k < prescribed_.size(); ++k) clamp_v_[k] = v[prescribed_[k]];
  clamp_until_ = until;
}

void Model::prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const {
  for (std::size_t k = 0; k < prescribed_.size(); ++k) {
    const std::size_t c = prescribed_[k];
    q[c] = clamp_q_[k] + clamp_v_[k] * std::min(t, clamp_until_);
    v[c] = t < clamp_until_ ? clamp_v_[k] : 0.0;
    a[c] = 0;
  }
}

void Model::bind_state(std::span<const double> q, std::span<const double> v, std::span<double> a, bool track) {
  const std::size_t n = lattice_.n;
  ctx_.x = q.data();
  ctx_.y = q.data() + n;
  ctx_.vx = v.data();
  ctx_.vy = v.data() + n;
  ctx_.ax = a.data();
  ctx_.ay = a.data() + n;
  ctx_.track = track;
}

void Model::accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  bind(t, q, v, a);
  accelerations_.run(team_size());
}

void Model::bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  System::bind(t, q, v, a);
  bind_state(q, v, a, true);
  if (ctx_.freeze) {  // (the first evaluation has no previous positions: it freezes nothing in between)
    const bool previous = !q_prev_.empty();
    if (!previous) q_prev_.resize(2 * lattice_.n);
    ctx_.x_prev = previous ? q_prev_.data() : nullptr;
    ctx_.y_prev = previous ? q_prev_.data() + lattice_.n : nullptr;
  }
}

void Model::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "model");
  archive.array("status", status_, status_.size());
  archive.array("past_cutoff", past_, past_.size());
  archive.array("cutoff", cutoff_, cutoff_.size());
  archive.array("frozen", frozen_, frozen_.size());
  archive.array("q_previous", q_prev_, q_prev_.size());
  if (!archive.loading()) return;
  for (std::uint8_t& s : status_) {
    if (s > kFreezing) archive.refuse("status", "holds a status no bond has (" + std::to_string(s) + ")");
    if (s == kFreezing) s = kBroken;  // (a checkpoint of an older build: its terms are frozen, as settled)
  }
  if (!q_prev_.empty()) {
    ctx_.x_prev = q_prev_.data();
    ctx_.y_prev = q_prev_.data() + lattice_.n;
  }
}

void Model::forces(std::span<const double> q, std::span<double> f) {
  const std::size_t n = lattice_.n;
  // Forces without damping: evaluate with zero velocities (the damping term vanishes exactly).
  bind_state(q, zero_v_, f, false);
  evaluation_.run(team_size());
  const double m = options_.node_mass;
  for (std::size_t k = 0; k < 2 * n; ++k) f[k] *= m;
}

Model::Energy Model::potential_energy(std::span<const double> q) {
  bind_state(q, zero_v_, scratch_a_, false);
  energy_.run(team_size());
  Energy e;
  const std::size_t blocks = blocks_.size() / 4;
  for (std::size_t k = 0; k < blocks; ++k) {
    e.pair += blocks_[2 * k];
    e.three_body += blocks_[2 * k + 1];
  }
  for (double c : frozen_) e.frozen += c;
  return e;
}

Eigen::Matrix2d Model::virial(std::span<const double> q) {
  bind_state(q, zero_v_, scratch_a_, false);
  virial_.run(team_size());
  Eigen::Matrix2d w = Eigen::Matrix2d::Zero();
  const std::size_t blocks = blocks_.size() / 4;
  for (std::size_t k = 0; k < blocks; ++k) {
    w(0, 0) += blocks_[4 * k];
    w(0, 1) += blocks_[4 * k + 1];
    w(1, 0) += blocks_[4 * k + 2];
    w(1, 1) += blocks_[4 * k + 3];
  }
  return w;
}

double Model::kinetic_energy(std::span<const double> v) const {
  // Fixed-order sum (single thread): the same bits for any number of threads.
  double e = 0;
  for (double x : v) e += x * x;
  return 0.5 * options_.node_mass * e;
}

int Model::pending_events() const {
  int k = 0;
  for (int w = 0; w < ForceContext::kMaxWorkers; ++w) k += ctx_.events[w];
  return k;
}
int Model::pending_breaks() const {
  int k = 0;
  for (int w = 0; w < ForceContext::kMaxWorkers; ++w) k += ctx_.breaks[w];
  return k;
}
int Model::nonfinite() const {
  int k = 0;
  for (int w = 0; w < ForceContext::kMaxWorkers; ++w) k += ctx_.nonfinite[w];
  return k;
}

void Model::take_events(std::vector<std::size_t>& out) {
  if (pending_events() == 0) return;
  for (std::size_t b = 0; b < past_.size(); ++b)
    if (past_[b] == 1) {
      past_[b] = 2;
      out.push_back(b);
    }
  for (int& e : ctx_.events) e = 0;
}

void Model::clear_breaks() {
  for (int& e : ctx_.breaks) e = 0;
}

std::string Model::diagnose_nonfinite(std::span<const double> q, std::span<const double> a) const {
  const std::size_t n = lattice_.n;
  std::ostringstream out;
  out.precision(6);
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(a[i]) && std::isfinite(a[n + i])) continue;
    out << "node " << i << " (reference position " << lattice_.rx[i] << ", " << lattice_.ry[i] << " m)";
    if (!std::isfinite(q[i]) || !std::isfinite(q[n + i])) {
      out << ": its position is not finite (the time step is too large for the forces reached)";
      return out.str();
    }
    for (int s = 0; s < 6; ++s) {
      const auto j = static_cast<std::size_t>(lattice_.nbr[6 * i + static_cast<std::size_t>(s)]);
      const std::size_t b = s < 3 ? 3 * i + static_cast<std::size_t>(s) : 3 * j + static_cast<std::size_t>(s - 3);
      if (j >= n || status_[b] != kIntact) continue;
      const double u = bond_length(b, q);
      if (!std::isfinite(u) || u == 0) {
        out << ": bond to node " << j << " has length " << u << " m (pair term f and cut-off h undefined)";
        return out.str();
      }
    }
    out << ": the three-body term of a neighbour (all bond lengths finite and non-zero)";
    return out.str();
  }
  return "no node with a non-finite acceleration";
}

}  // namespace frac::rubber
