#include "dem/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/finite.hpp"
#include "core/parallel.hpp"

namespace frac::dem {

double LayerMotion::displacement(double t) const {
  if (speed == 0) return 0;
  if (t < ramp) return 0.5 * speed / ramp * t * t;
  return 0.5 * speed * ramp + speed * (t - ramp);
}
double LayerMotion::velocity(double t) const {
  if (speed == 0) return 0;
  return t < ramp ? speed * t / ramp : speed;
}
double LayerMotion::acceleration(double t) const {
  if (speed == 0) return 0;
  return t < ramp ? speed / ramp : 0;
}

Model::Model(const mesh::CellMesh& mesh, const Material& material, const Physics& physics, const ContactLawTable& laws)
    : bodies_(make_bodies(mesh, material)), material_(material), physics_(physics) {
  // The beams' geometry is kept even when they are off (a run file records every mesh beam: intact flags
  // and strains); off, the Simulation marks them all broken and the term is not in the list.
  beams_ = Beams(mesh, material);
  if (physics.beams) terms_.push_back("beams");
  const std::vector<std::string> law_names = physics.contact_laws();
  laws_ = make_contact_laws(laws, law_names, material);
  law_power_.assign(laws_.size(), 0.0);
  contacts_.set_laws(laws_.size());
  terms_.insert(terms_.end(), laws_.names.begin(), laws_.names.end());
  if (physics.contacts) search_ = ContactSearch(mesh, bodies_);
  force_.assign(size(), 0.0);
  inv_mass_.resize(size());
  for (std::size_t k = 0; k < bodies_.n; ++k) {
    inv_mass_[k] = inv_mass_[bodies_.n + k] = 1.0 / bodies_.mass[k];
    inv_mass_[2 * bodies_.n + k] = 1.0 / bodies_.inertia[k];
  }
  make_phases();
}

void Model::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "model");
  archive.value("evaluations", evaluations_);
  beams_.visit_state(archive);
  if (physics_.contacts) search_.visit_state(archive);
}

void Model::accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  bind(t, q, v, a);
  phases_.run(team_size());
}

void Model::bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  System::bind(t, q, v, a);
  ++evaluations_;
  if (physics_.contacts) search_.bind(q, contacts_);
  zero_.reserve(static_cast<std::size_t>(max_threads()));
  contacts_.reserve_power_parts(static_cast<std::size_t>(max_threads()));
}

// One parallel loop a phase, each thread taking the same cells in every per-cell loop (static_range), so that it
// finds the values where it left them, and the contacts it filled, for the contact laws. The beams, when on, come
// first onto the forces and write them (no pass to zero them first: a loop fewer).
void Model::make_phases() {
  const bool beams = physics_.beams, contacts = physics_.contacts;
  if (!beams)
    phases_.add({"forces: zero",
                 false,
                 [this](std::size_t t, std::size_t nt) {
                   double* force = force_.data();
                   coordinate_ranges(size(), coordinate_blocks(), t, nt, [&](std::size_t first, std::size_t last) {
#pragma omp simd
                     for (std::size_t k = first; k < last; ++k) force[k] = 0.0;
                   });
                 },
                 {}});
  if (contacts) phases_.add(search_.start_phases());
  if (beams)
    phases_.add(
        {"beams: forces", false, [this](std::size_t t, std::size_t nt) { beams_.beam_pass(bound_q_, t, nt); }, {}});
  if (contacts) phases_.add(search_.finish_phases());
  if (beams)
    phases_.add(
        {"beams: gather", false, [this](std::size_t t, std::size_t nt) { beams_.gather(force_, false, t, nt); }, {}});
  if (contacts) {
    phases_.add({"contact laws", false, [this](std::size_t t, std::size_t) { contact_laws_part(t); }, {}});
    phases_.add({"contact forces", false, [this](std::size_t t, std::size_t nt) { contact_forces_part(t, nt); }, {}});
  }
  phases_.add({"accelerations", false, [this](std::size_t t, std::size_t nt) { accelerations_part(t, nt); }, {}});
  phases_.add({"forces: sums", true, [this](std::size_t, std::size_t nt) { sums(nt); }, {}});
}

void Model::contact_laws_part(std::size_t t) {
  // The block this thread filled.
  const Range mine = contacts_.block[t];
  contact_kinematics(contacts_, bodies_, bound_q_, bound_v_, mine);
  apply_contact_laws(laws_, contacts_, mine);
}

void Model::contact_forces_part(std::size_t t, std::size_t nt) {
  // The laws' exact power sums over this thread's block of the list (merged after the team), and the contacts'
  // forces, summed over the laws, onto its own cells in contact order.
  const std::size_t count = contacts_.block[nt - 1].last;  // (the blocks cover the list in order)
  for (std::size_t l = 0; l < laws_.size(); ++l) law_power_part(contacts_, l, count, t);
  add_contact_forces_of_team(contacts_, bodies_.n, bound_q_, force_, t, nt);
}

void Model::accelerations_part(std::size_t t, std::size_t nt) {
  // The accelerations, and in the same pass whether every force is finite.
  const double* force = force_.data();
  const double* inv_mass = inv_mass_.data();
  double* acc = bound_a_.data();
  std::uint64_t bad = 0;
  coordinate_ranges(size(), coordinate_blocks(), t, nt, [&](std::size_t first, std::size_t last) {
    double* __restrict out = acc;
    const double* __restrict f = force;
    const double* __restrict w = inv_mass;
#pragma omp simd reduction(| : bad)
    for (std::size_t k = first; k < last; ++k) {
      const double fk = f[k];
      out[k] = fk * w[k];
      bad |= non_finite_bit(fk);
    }
  });
  zero_[t] = non_finite_seen(bad) ? 1.0 : 0.0;
}

void Model::sums(std::size_t nt) {
  for (std::size_t l = 0; l < laws_.size(); ++l) law_power_[l] = law_power_of_parts(contacts_, l, nt);
  double zero = 0;
  for (std::size_t s = 0; s < nt; ++s) zero += zero_[s];
  // A non-finite force is traced to the first term that made it (the run stops at this step).
  if (zero != 0.0 && non_finite_term_.empty()) blame_non_finite(bound_q_, bound_v_);
  ExactSum boundary;
  for (const Prescribed& p : prescribed_) {
    const LayerMotion& m = layers_[static_cast<std::size_t>(p.layer)];
    const double m_k = 1.0 / inv_mass_[p.index];
    boundary.add((m_k * m.acceleration(bound_t_) - force_[p.index]) * m.velocity(bound_t_));
  }
  boundary_power_ = boundary.value();
}

std::int64_t Model::calls(std::string_view term) const {
  return std::find(terms_.begin(), terms_.end(), term) != terms_.end() ? evaluations_ : 0;
}

void Model::blame_non_finite(std::span<const double> q, std::span<const double> v) {
  // The same evaluation again, one term at a time, the forces of the terms so far summed from zero (the contact
  // list is kept): the beams, then the contact laws one after another.
  auto first_non_finite = [&](const std::string& term) {
    for (std::size_t i = 0; i < force_.size(); ++i) {
      if (!std::isfinite(force_[i])) {
        non_finite_term_ = term;
        non_finite_index_ = i;
        return true;
      }
    }
    return false;
  };
  std::fill(force_.begin(), force_.end(), 0.0);
  if (physics_.beams) {
    beams_.add_forces(q, force_);
    if (first_non_finite("beams")) return;
  }
  if (laws_.size() == 0) return;
  const std::vector<double> beam_force = force_;
  const Range all{0, contacts_.size()};
  contact_kinematics(contacts_, bodies_, q, v, all);
  for (std::size_t l = 0; l < laws_.size(); ++l) {
    laws_.laws[l]->add(contacts_, all, contacts_.law_power[l].data());
    force_ = beam_force;
    add_contact_forces(contacts_, bodies_.n, q, force_);
    if (first_non_finite(laws_.names[l])) return;
  }
}

void Model::prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const {
  for (const Prescribed& p : prescribed_) {
    const LayerMotion& m = layers_[static_cast<std::size_t>(p.layer)];
    q[p.index] = p.q0 + m.displacement(t);
    v[p.index] = m.velocity(t);
    a[p.index] = m.acceleration(t);
  }
}

int Model::add_layer(const LayerMotion& motion) {
  layers_.push_back(motion);
  return static_cast<int>(layers_.size()) - 1;
}

void Model::add_prescribed(std::size_t index, double q0, int layer) {
  prescribed_.push_back({index, q0, layer});
  prescribed_index_.push_back(index);
}

std::array<double, 2> Model::kinetic_energy(std::span<const double> v) const {
  // Exact sums (core/exact_sum) of each thread's cells, merged: the same value whatever the thread count or the
  // cells' order.
  const std::size_t n = bodies_.n;
  for (auto& part : energy_parts_) part.assign(static_cast<std::size_t>(max_threads()), ExactSum{});
  const double* m = bodies_.mass.data();
  const double* inertia = bodies_.inertia.data();
  as_team(n > kMinParallelCoordinates, [&] {
    const Range mine = this_thread_range(n);
    const auto t = static_cast<std::size_t>(thread_index());
    ExactSum& translational = energy_parts_[0][t];
    ExactSum& rotational = energy_parts_[1][t];
    for (std::size_t k = mine.first; k < mine.last; ++k) {
      translational.add(0.5 * m[k] * (v[k] * v[k] + v[n + k] * v[n + k]));
      rotational.add(0.5 * inertia[k] * v[2 * n + k] * v[2 * n + k]);
    }
  });
  return {sum_of(energy_parts_[0]), sum_of(energy_parts_[1])};
}

}  // namespace frac::dem
