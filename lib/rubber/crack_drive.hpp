#pragma once
// A driven seed crack (not in the paper; a switch of the stretch scene, crack.drive_speed and
// crack.drive_length): a "knife" starts at the tip of the seed cut and moves along the crack line at a
// given lab speed, removing for good (like the seed) each bond crossing the line as it passes it, up to a
// given length beyond the seed; after that the crack is on its own. In lattice models a running crack can
// exist at loads where a static notch cannot start one (lattice trapping: the static tip blunts, a moving
// one has no time to), so the drive starts the crack moving.
//
// The knife is at reference x_min + seed_length + (drive_speed / λx) t: drive_speed is its lab speed in the
// far field, comparable with the lattice's c_T and c_L along x. A bond crossing the line at reference x
// (crossing x − x_min in [seed_length, seed_length + drive_length)) is removed at
// t = λx (x − x_min − seed_length) / drive_speed. A removed bond takes its energy with it: cut() returns
// the change of the potential energy the cuts made, which the run books as the knife's work.
#include <cstddef>
#include <span>
#include <vector>

#include "core/state_archive.hpp"
#include "rubber/crack.hpp"
#include "rubber/model.hpp"

namespace frac::rubber {

class CrackDrive {
 public:
  // speed > 0 (m/s, lab), length > 0 (m, reference), stretch_x > 0 (λx).
  CrackDrive(const CrackPath& path, double seed_length, double speed, double length, double stretch_x);

  // Removes every scheduled bond whose time has come (cut time ≤ t) and returns how many it removed.
  // With q given, also returns through `energy_change` U(after) − U(before) at q (0 if nothing was cut).
  std::size_t cut(Model& model, double t, std::span<const double> q, double& energy_change);

  std::size_t scheduled() const { return bond_.size(); }
  std::size_t done() const { return next_; }
  bool finished() const { return next_ == bond_.size(); }
  std::size_t bond(std::size_t k) const { return bond_[k]; }
  double cut_time(std::size_t k) const { return time_[k]; }  // s
  double end_time() const { return end_time_; }              // s: when the knife reaches the end
  double end_reference_x() const { return end_x_; }          // m: reference x where the drive stops
  // The state a continuation needs (core/state_archive): how many bonds the knife has cut.
  void visit_state(StateArchive& archive);

 private:
  std::vector<std::size_t> bond_;  // scheduled crossing bonds, by crossing x
  std::vector<double> time_;       // their cut times (non-decreasing)
  std::size_t next_ = 0;
  double end_time_ = 0, end_x_ = 0;
};

}  // namespace frac::rubber
