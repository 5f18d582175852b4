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

Model::Model(const mesh::CellMesh& mesh, const Material& material, const Physics& physics,
             const ContactLawTable& laws)
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
}

void Model::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "model");
  archive.value("evaluations", evaluations_);
  beams_.visit_state(archive);
  if (physics_.contacts) search_.visit_state(archive);
}

void Model::accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) {
  const std::size_t n = size();
  double* force = force_.data();
  ++evaluations_;
  // The beams, when on, come first and write the forces (no pass to zero them first: a loop fewer).
  const bool beams_on = physics_.beams;
  const bool contact_list = physics_.contacts;
  const auto most = static_cast<std::size_t>(max_threads());
  if (contact_list) search_.reserve_threads(most, contacts_);
  zero_.reserve(most);
  const double* inv_mass = inv_mass_.data();
  double* acc = a.data();
  // One parallel region, barriers only where a thread reads what another wrote. Each thread takes the same cells
  // in every per-cell loop (static_range), so it finds the values where it left them, and the contacts it
  // filled, for the contact laws.
  as_team(bodies_.n > kMinParallelItems, [&] {
    const auto nt = static_cast<std::size_t>(thread_count());
    if (!beams_on) {
      this_thread_coordinate_ranges(n, coordinate_blocks(), [&](std::size_t first, std::size_t last) {
#pragma omp simd
        for (std::size_t k = first; k < last; ++k) force[k] = 0.0;
      });
    }
    if (contact_list) search_.find_start(q);  // (this thread's cells: their positions alone)
    team_barrier();
    // (Every thread's part of the search started: the beams and the pairs read the other threads' cells.)
    if (beams_on) beams_.beam_pass(q);
    if (contact_list) {
      search_.find_finish(q, contacts_);  // (its barriers come after every beam's force)
    } else {
      team_barrier();
    }
    if (beams_on) beams_.gather(force_, false);  // (delivers its power through the beam energy, not as work)
    if (contact_list) {
      // The block this thread filled (not contacts_.mine(): the list's `blocks` is set after the barrier).
      const Range mine{contacts_.block[static_cast<std::size_t>(thread_index())]};
      contact_kinematics(contacts_, bodies_, q, v, mine);
      apply_contact_laws(laws_, contacts_, mine);
      // The first thread adds its own block's forces onto its cells before the barrier: they come first onto
      // them, and no other thread writes them. (It is the one that waits here: it reads the first rows of the
      // next thread's cells, whose loops then wait for its copies of their lines to be invalidated.)
      if (thread_index() == 0) add_contact_forces_of_team(contacts_, bodies_.n, q, force_, Range{0, 1});
    }
    team_barrier();
    // The list's size and diagnostics by one thread (read after the team); each thread the power sums of the
    // blocks of contacts that start in its part of the list (added up after the team) and the contacts'
    // forces, summed over the terms, onto its own cells in contact order; no barrier after.
    if (thread_index() == 0) {
      teams_ = nt;
      if (contact_list) search_.find_end(contacts_);
    }
    if (contact_list) {
      const std::size_t count = contacts_.block[nt - 1].last;  // (the blocks cover the list in order)
      const Range mine{contacts_.block[static_cast<std::size_t>(thread_index())]};
      for (std::size_t l = 0; l < laws_.size(); ++l) law_block_powers(contacts_, l, count, mine);
      const std::size_t first_block = thread_index() == 0 ? 1 : 0;  // (the first thread's own: added above)
      add_contact_forces_of_team(contacts_, bodies_.n, q, force_, Range{first_block, nt});
    }
    // The accelerations, and in the same pass whether every force is finite.
    std::uint64_t bad = 0;
    this_thread_coordinate_ranges(n, coordinate_blocks(), [&](std::size_t first, std::size_t last) {
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
    zero_.mine() = non_finite_seen(bad) ? 1.0 : 0.0;
  });
  for (std::size_t l = 0; l < laws_.size(); ++l) law_power_[l] = law_power_of_blocks(contacts_, l);
  double zero = 0;
  for (std::size_t s = 0; s < teams_; ++s) zero += zero_[s];
  // A non-finite force is traced to the first term that made it (the run stops at this step).
  if (zero != 0.0 && non_finite_term_.empty()) blame_non_finite(q, v);
  boundary_power_ = 0;
  for (const Prescribed& p : prescribed_) {
    const LayerMotion& m = layers_[static_cast<std::size_t>(p.layer)];
    const double m_k = 1.0 / inv_mass_[p.index];
    boundary_power_ += (m_k * m.acceleration(t) - force_[p.index]) * m.velocity(t);
  }
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
  // Sums over fixed blocks of cells, in cell order within a block, then over the blocks in order: the same
  // bits whatever the thread count, and each thread reads mostly the velocities it wrote.
  constexpr std::size_t kBlock = 64;
  const std::size_t n = bodies_.n, blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::array<double, 2>>& part = energy_blocks_;
  part.resize(blocks);
  const double* m = bodies_.mass.data();
  const double* inertia = bodies_.inertia.data();
  as_team(n > kMinParallelCoordinates, [&] {
    const Range mine = this_thread_range(blocks);
    for (std::size_t b = mine.first; b < mine.last; ++b) {
      double et = 0, er = 0;
      for (std::size_t k = b * kBlock; k < std::min(n, (b + 1) * kBlock); ++k) {
        et += 0.5 * m[k] * (v[k] * v[k] + v[n + k] * v[n + k]);
        er += 0.5 * inertia[k] * v[2 * n + k] * v[2 * n + k];
      }
      part[b] = {et, er};
    }
  });
  double et = 0, er = 0;
  for (const auto& p : part) {
    et += p[0];
    er += p[1];
  }
  return {et, er};
}

}  // namespace frac::dem
