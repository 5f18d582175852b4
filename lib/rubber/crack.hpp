#pragma once
// The crack path and its tip (physics/rubber-lattice.md §6). The path is the line y = notch_y of the
// mesh, between its two middle node levels; the bonds crossing it, sorted by where they cross, are the
// bonds a straight crack along x breaks. The seed crack removes those crossing within a length L0 of the
// left edge. The tip is the furthest (largest reference crossing x) crossing bond that is broken:
// removed, failed irreversibly, or longer than its cut-off (h < 1/2). Its lab position is the mean of
// the current x of its two nodes.
#include <cstddef>
#include <span>
#include <vector>

#include "mesh/node_mesh.hpp"
#include "rubber/model.hpp"

namespace frac::rubber {

class CrackPath {
 public:
  CrackPath(const mesh::NodeMesh& mesh, const Lattice& lattice);

  // Removes (cuts on purpose) the crossing bonds with crossing x − x_min < length; returns how many.
  std::size_t seed(Model& model, double length) const;

  // Gives every existing bond that does not cross the path the cut-off `cutoff` (a tougher bulk: the
  // path is a weak plane); returns how many.
  std::size_t set_bulk_cutoff(Model& model, double cutoff) const;

  struct Tip {
    bool found = false;
    std::size_t bond = 0;    // forward bond id of the tip bond
    double reference_x = 0;  // m, where it crosses the path in the reference lattice
    double lab_x = 0;        // m, current x of the crossing (mean of its nodes)
    std::size_t broken = 0;  // broken crossing bonds
  };
  Tip tip(const Model& model, std::span<const double> q) const;

  // The first crossing bond ahead of the tip that still holds (for a tip kick), or the end.
  std::size_t next_intact(const Model& model, std::span<const double> q) const;

  std::size_t size() const { return bond_.size(); }
  double x_min() const { return x_min_; }
  double x_max() const { return x_max_; }
  double line_y() const { return y_; }
  std::size_t bond(std::size_t k) const { return bond_[k]; }
  double crossing(std::size_t k) const { return cross_[k]; }

 private:
  std::vector<std::size_t> bond_;  // crossing bonds, by crossing x
  std::vector<double> cross_;      // their crossing x (reference)
  double y_ = 0, x_min_ = 0, x_max_ = 0;
};

}  // namespace frac::rubber
