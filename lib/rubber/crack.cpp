#include "rubber/crack.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace frac::rubber {

CrackPath::CrackPath(const mesh::NodeMesh& mesh, const Lattice& L) : y_(mesh.notch_y) {
  if (L.n == 0) return;
  x_min_ = *std::min_element(L.rx.begin(), L.rx.end());
  x_max_ = *std::max_element(L.rx.begin(), L.rx.end());
  std::vector<std::size_t> bonds;
  std::vector<double> cross;
  for (std::size_t b = 0; b < 3 * L.n; ++b) {
    if (!L.exists[b] || L.shift[2 * b] != 0 || L.shift[2 * b + 1] != 0) continue;  // no wrap bonds
    const std::size_t i = b / 3, j = L.bond_other(b);
    const double si = L.ry[i] - y_, sj = L.ry[j] - y_;
    if ((si < 0) == (sj < 0)) continue;
    bonds.push_back(b);
    cross.push_back(L.rx[i] + (L.rx[j] - L.rx[i]) * si / (si - sj));
  }
  std::vector<std::size_t> order(bonds.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cross[a] < cross[b]; });
  for (std::size_t k : order) {
    bond_.push_back(bonds[k]);
    cross_.push_back(cross[k]);
  }
}

std::size_t CrackPath::seed(Model& model, double length) const {
  std::size_t cut = 0;
  for (std::size_t k = 0; k < bond_.size(); ++k)
    if (cross_[k] - x_min_ < length && model.status(bond_[k]) == kIntact) {
      model.remove_bond(bond_[k]);
      ++cut;
    }
  return cut;
}

std::size_t CrackPath::set_bulk_cutoff(Model& model, double cutoff) const {
  const Lattice& L = model.lattice();
  std::vector<std::uint8_t> on_path(L.bonds(), 0);
  for (std::size_t b : bond_) on_path[b] = 1;
  std::size_t set = 0;
  for (std::size_t b = 0; b < L.bonds(); ++b)
    if (L.exists[b] && !on_path[b]) {
      model.set_cutoff(b, cutoff);
      ++set;
    }
  return set;
}

CrackPath::Tip CrackPath::tip(const Model& model, std::span<const double> q) const {
  Tip t;
  const std::size_t n = model.nodes();
  for (std::size_t k = 0; k < bond_.size(); ++k) {
    if (model.holds(bond_[k], q)) continue;
    ++t.broken;
    t.found = true;
    t.bond = bond_[k];
    t.reference_x = cross_[k];
  }
  if (t.found) {
    const std::size_t i = t.bond / 3, j = model.lattice().bond_other(t.bond);
    t.lab_x = 0.5 * (q[i] + q[j < n ? j : i]);
  }
  return t;
}

std::size_t CrackPath::next_intact(const Model& model, std::span<const double> q) const {
  const Tip t = tip(model, q);
  for (std::size_t k = 0; k < bond_.size(); ++k)
    if ((!t.found || cross_[k] > t.reference_x) && model.holds(bond_[k], q)) return k;
  return bond_.size();
}

}  // namespace frac::rubber
