#pragma once
// The polygon DEM as a dynamics::System: the force terms a scene names, composed into a list of phases at
// construction (core/phases; a term that is off is not in the list: it is never called and costs nothing), the
// prescribed boundary coordinates of the loading, and the energy ledger (the power of every
// non-conservative term, integrated over time).
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/parallel.hpp"
#include "core/state_registry.hpp"
#include "dem/beams.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_laws.hpp"
#include "dem/contact_list.hpp"
#include "dem/contact_search.hpp"
#include "dem/material.hpp"
#include "dynamics/integrator.hpp"

namespace frac::dem {

// A prescribed coordinate: index into q, and its trajectory q(t) = q0 + s(t), with s, ṡ, s̈ from the
// loading protocol (shared by every coordinate of one boundary layer through `layer`).
struct Prescribed {
  std::size_t index;
  double q0;
  int layer;  // index into Model::layers
};
struct LayerMotion {
  // Displacement s(t) of the layer along its coordinate: constant acceleration from rest for t < ramp,
  // then constant speed `speed`. speed = 0 holds the coordinate fixed.
  double speed = 0, ramp = 0;
  double displacement(double t) const;
  double velocity(double t) const;
  double acceleration(double t) const;
};

class Model final : public dynamics::System {
 public:
  // The contact laws the physics names, from `laws` (the paper's by default; tests add their own).
  Model(const mesh::CellMesh& mesh, const Material& material, const Physics& physics,
        const ContactLawTable& laws = contact_law_table());
  Model(const Model&) = delete;  // (its phases call it where it is)
  Model& operator=(const Model&) = delete;

  // dynamics::System: the evaluation is its phases, on a team of its own (accelerations) or in a step's.
  void accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override;
  void bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override;
  Phases force_phases() override { return phases_; }
  std::size_t team_size() const override { return frac::team_size(bodies_.n > kMinParallelItems); }
  std::size_t coordinate_blocks() const override { return 3; }  // x, y, φ of every cell
  std::span<const std::size_t> prescribed() const override { return prescribed_index_; }
  void prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const override;

  // Loading: prescribe a coordinate to follow `layer`'s motion from its value q0.
  int add_layer(const LayerMotion& motion);
  void add_prescribed(std::size_t index, double q0, int layer);

  const Bodies& bodies() const { return bodies_; }
  Beams& beams() { return beams_; }
  const Beams& beams() const { return beams_; }
  const ContactList& contacts() const { return contacts_; }
  const Material& material() const { return material_; }
  const Physics& physics() const { return physics_; }
  std::size_t size() const { return 3 * bodies_.n; }

  // Forces (fx, fy, torque layout) of the last evaluation: the total on every coordinate.
  std::span<const double> forces() const { return force_; }
  // The power of contact law l (contact_laws().names[l]) at the last evaluation (W), and of the boundary (what
  // the prescribed motion must supply beyond the other forces: Σ (m a − F)·v over the prescribed coordinates).
  // (The beams deliver theirs through their energy.)
  double law_power(std::size_t l) const { return law_power_[l]; }
  double boundary_power() const { return boundary_power_; }
  const ContactLaws& contact_laws() const { return laws_; }
  // The force terms on, by name, in the order they run: "beams" (when on), then the contact laws.
  const std::vector<std::string>& terms() const { return terms_; }
  // How often a term ran: every evaluation for a term on, 0 for one that is off (tests check that such a term
  // never runs).
  std::int64_t calls(std::string_view term) const;
  // The first term whose forces became non-finite at an evaluation ("" if none), and the coordinate index
  // (0..3N) where it happened.
  const std::string& non_finite_term() const { return non_finite_term_; }
  std::size_t non_finite_index() const { return non_finite_index_; }

  // Kinetic energies at (q, v): translational, rotational, J.
  std::array<double, 2> kinetic_energy(std::span<const double> v) const;

  // The state a continuation needs (core/state_archive), under "model/": the beams and the neighbour list;
  // declared to a run's registry (core/state_registry).
  void visit_state(StateArchive& archive);
  void declare_state(StateRegistry& registry) {
    registry.other([this](StateArchive& a) { visit_state(a); });
  }

 private:
  // After an evaluation whose forces are not all finite: the first term, and the coordinate, where they
  // became non-finite (non_finite_term_, non_finite_index_).
  void blame_non_finite(std::span<const double> q, std::span<const double> v);
  // The evaluation's phases, and the bodies of its own: thread t of a team of nt.
  Phases phases_;
  void make_phases();
  void contact_laws_part(std::size_t t);
  void contact_forces_part(std::size_t t, std::size_t nt);
  void accelerations_part(std::size_t t, std::size_t nt);
  void sums(std::size_t nt);  // the laws' powers, the non-finite check, the boundary's power
  Bodies bodies_;
  Material material_;
  Physics physics_;
  Beams beams_;
  ContactSearch search_;
  mutable std::array<std::vector<ExactSum>, 2> energy_parts_;  // kinetic_energy's sums, a thread each
  ContactList contacts_;
  ContactLaws laws_;
  std::vector<std::string> terms_;
  std::vector<double> force_;
  std::vector<double> law_power_;
  std::int64_t evaluations_ = 0;
  double boundary_power_ = 0;
  std::string non_finite_term_;
  std::size_t non_finite_index_ = 0;
  std::vector<LayerMotion> layers_;
  std::vector<Prescribed> prescribed_;
  std::vector<std::size_t> prescribed_index_;
  std::vector<double> inv_mass_;  // per coordinate: 1/m, 1/m, 1/I
  TeamSlots<double> zero_;        // per thread of the evaluation's team: Σ F·0 over its coordinates
};

}  // namespace frac::dem
