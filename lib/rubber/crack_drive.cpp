#include "rubber/crack_drive.hpp"

#include "core/error.hpp"

namespace frac::rubber {

CrackDrive::CrackDrive(const CrackPath& path, double seed_length, double speed, double length, double stretch_x) {
  if (!(speed > 0) || !(length > 0) || !(stretch_x > 0))
    throw UsageError("crack drive: speed, length and stretch must be positive");
  const double start = path.x_min() + seed_length;
  end_x_ = start + length;
  end_time_ = stretch_x * length / speed;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const double x = path.crossing(k);
    if (x < start || x >= end_x_) continue;
    bond_.push_back(path.bond(k));
    time_.push_back(stretch_x * (x - start) / speed);
  }
}

std::size_t CrackDrive::cut(Model& model, double t, std::span<const double> q, double& energy_change) {
  energy_change = 0;
  if (next_ == bond_.size() || time_[next_] > t) return 0;
  const double before = model.potential_energy(q).total();
  std::size_t removed = 0;
  for (; next_ < bond_.size() && time_[next_] <= t; ++next_)
    if (model.status(bond_[next_]) == kIntact) {
      model.remove_bond(bond_[next_]);
      ++removed;
    }
  if (removed > 0) energy_change = model.potential_energy(q).total() - before;
  return removed;
}

void CrackDrive::visit_state(StateArchive& archive) {
  StateArchive::Scope scope(archive, "drive");
  archive.value("cut", next_);
  if (archive.loading() && next_ > bond_.size()) archive.refuse("cut", "more cuts than the knife has bonds");
}

}  // namespace frac::rubber
