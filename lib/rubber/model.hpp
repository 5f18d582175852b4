#pragma once
// Marder's rubber lattice as a dynamics::System: nodes of equal mass m on a triangular lattice, the
// pair + three-body bond law of bond_law.hpp, optional Kelvin damping along bonds, clamped nodes.
// Coordinates q = (x of every node, then y of every node), SI units.
//
// Bonds fail smoothly through h (reversible, as in the paper: a bond past u_c carries no force and the
// constant f(u_c), and would pull again if it came back). With irreversible breaking, a bond whose
// length exceeds u_c + break_extra (where h is already ≈ 0) is removed for good and keeps its constant
// pair energy 2 f(u_c); the three-body energy it still had, h·g ≈ e^{−break_extra/w}·g, is lost.
// Bonds removed on purpose (the seed crack) carry no energy and no force.
//
// Energy-neutral failure (Failure::freeze, not in the paper): a bond breaks irreversibly when it first
// passes u_c, and every three-body term that contains it, h_s h_t g(a_s·a_t) at either end, is frozen into
// a constant energy of its node at its value when the bond crossed u_c, as f is frozen at f(u_c). The
// bond carries no force from the evaluation in which it is found past u_c on. The crossing lies between
// the last step's configuration and this one (on the straight line each node moved along); freezing
// there keeps the energy error of a failure O(dt) and of either sign, so that it does not accumulate.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/state_archive.hpp"
#include "dynamics/integrator.hpp"
#include "rubber/bond_law.hpp"
#include "rubber/forces.hpp"
#include "rubber/lattice.hpp"

namespace frac::rubber {

// What a failing bond takes with it: the paper's law (its three-body terms fade through h, or go with it
// when it is removed) or the energy-neutral law (frozen at failure; breaking at u_c, break_extra unused).
enum class Failure { paper, freeze };

struct ModelOptions {
  BondLaw law;
  Failure failure = Failure::paper;
  double node_mass = 1;                     // kg
  DampingKind damping = DampingKind::none;  // Kelvin damping along bonds
  double beta = 0;                          // kg/s: F_i += β ((v_j − v_i)·û) û
  double damping_onset = 0;                 // m: near_failure damping ramps from 0 here to β at u_c
  double break_extra = std::numeric_limits<double>::infinity();  // m: irreversible past u_c + this
  // The three-body residual c_st (three_body_residual.hpp), 36 values in J, or empty: the paper's law.
  std::vector<double> residual;
  int threads = 1;
  // Fuse the three force passes row by row when the mesh has the row-major layout of mesh-gen (the
  // same numbers either way; false forces three passes over all nodes).
  bool fused = true;
};

class Model final : public dynamics::System {
 public:
  Model(Lattice lattice, ModelOptions options);
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  const Lattice& lattice() const { return lattice_; }
  const ModelOptions& options() const { return options_; }
  std::size_t nodes() const { return lattice_.n; }
  double node_mass() const { return options_.node_mass; }
  int threads() const { return threads_; }
  bool fused() const { return fused_; }

  // Periodic boxes: image shifts of the wrap bonds for a box deformed homogeneously by F (lab shift =
  // F · reference shift). The default is F = I.
  void set_box(const Eigen::Matrix2d& F);

  // Bond state, by forward bond id (Lattice).
  void remove_bond(std::size_t b);                // cut on purpose: no energy, no force
  void set_cutoff(std::size_t b, double cutoff);  // u_c of one bond (toughening)
  double cutoff(std::size_t b) const { return cutoff_[b]; }
  std::uint8_t status(std::size_t b) const { return status_[b]; }
  // Bond intact now: exists, not removed or broken, and shorter than its u_c (h > 1/2) at q.
  bool holds(std::size_t b, std::span<const double> q) const;
  double bond_length(std::size_t b, std::span<const double> q) const;

  // Toughening of the retracting crack faces: raises to `cutoff` the cut-off of every intact bond shorter
  // than `trigger` that has an end on a crack face (a node with a bond removed, broken or past its
  // cut-off) and a lower cut-off. Returns how many bonds it raised.
  std::size_t toughen(std::span<const double> q, double trigger, double cutoff);

  // Clamps: the given nodes keep the positions they have in q, with zero velocity; or, with v and
  // `until` > 0, move at the constant velocity v (per coordinate, like q) from q at t = 0 until `until`,
  // then stay.
  void clamp(std::span<const std::size_t> nodes, std::span<const double> q);
  void clamp(std::span<const std::size_t> nodes, std::span<const double> q, std::span<const double> v, double until);
  std::span<const std::size_t> clamped_nodes() const { return clamped_; }

  // dynamics::System: the evaluation is its phases (core/phases) on a team of threads() threads: the passes of
  // forces.hpp, then (energy-neutral failure) the positions the next evaluation's failures start from.
  void accelerations(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override;
  void bind(double t, std::span<const double> q, std::span<const double> v, std::span<double> a) override;
  Phases force_phases() override { return accelerations_; }
  std::size_t team_size() const override { return static_cast<std::size_t>(threads_); }
  std::size_t coordinate_blocks() const override { return 2; }  // x, y of every node
  std::span<const std::size_t> prescribed() const override { return prescribed_; }
  void prescribe(double t, std::span<double> q, std::span<double> v, std::span<double> a) const override;

  // Evaluations at a configuration (no events, no breaking, no damping).
  // frozen: the constants of the three-body terms frozen by energy-neutral failure.
  struct Energy {
    double pair = 0, three_body = 0, frozen = 0;
    double total() const { return pair + three_body + frozen; }
  };
  Energy potential_energy(std::span<const double> q);
  void forces(std::span<const double> q, std::span<double> f);  // −∇U
  // Σ_i Σ_s (∂E_i/∂a_s) ⊗ a_s (J); for a homogeneous state, dU/dF = virial · F⁻ᵀ.
  Eigen::Matrix2d virial(std::span<const double> q);
  double kinetic_energy(std::span<const double> v) const;

  // After accelerations(): counts since the last take (bonds newly beyond u_c, irreversible breaks,
  // nodes with a non-finite force).
  int pending_events() const;
  int pending_breaks() const;
  int nonfinite() const;
  // Appends the bonds newly beyond u_c to `out` and marks them recorded; clears the counters.
  void take_events(std::vector<std::size_t>& out);
  void clear_breaks();
  // The state a continuation needs (core/state_archive), under "model/": every bond's status, whether it went past
  // u_c, its cut-off (toughening raises them), and the frozen three-body energies with the positions they are
  // frozen from (Failure::freeze).
  void visit_state(StateArchive& archive);
  // Describes the first node whose acceleration in `a` is not finite and the term that made it.
  std::string diagnose_nonfinite(std::span<const double> q, std::span<const double> a) const;

 private:
  void bind_state(std::span<const double> q, std::span<const double> v, std::span<double> a, bool track);
  // The phase lists: each phase splits its nodes (or rows, or energy blocks) by thread (worker_range), and every
  // node's result is computed by the same instructions whichever thread runs it, so the thread count never
  // changes a bit of the result. evaluation_: bonds, centres and gather at the bound state (fused row by row
  // when the layout allows); accelerations_: evaluation_ and the previous positions; energy_, virial_: the
  // observables' passes.
  Phases evaluation_, accelerations_, energy_, virial_;
  void make_phases();
  Phase bonds_phase();
  Phase centres_phase();
  std::pair<std::size_t, std::size_t> rows_of(std::size_t worker, std::size_t workers) const;

  Lattice lattice_;
  ModelOptions options_;
  int threads_ = 1;
  std::unique_ptr<const ForcePasses> passes_;
  ForceContext ctx_;
  std::vector<std::uint8_t> status_, past_;
  std::vector<double> cutoff_, shift_;
  std::vector<BondData> bond_;
  std::vector<double> D_, blocks_, scratch_a_, zero_v_;
  std::vector<std::size_t> clamped_, prescribed_;
  std::vector<double> clamp_q_;  // positions of the prescribed coordinates (at t = 0)
  std::vector<double> clamp_v_;  // their velocities until clamp_until_ (zero for fixed clamps)
  double clamp_until_ = 0;
  std::vector<std::uint8_t> face_;  // per node, for toughen()
  std::vector<double> frozen_;      // per node, J: its frozen three-body terms (Failure::freeze)
  std::vector<double> q_prev_;      // with Failure::freeze: q at the last accelerations(), or empty
  bool fused_ = false;
  std::size_t rows_ = 0, row_len_ = 0;
};

}  // namespace frac::rubber
