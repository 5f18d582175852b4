#pragma once
// The state a run carries from step to step, declared once: per-cell (per-node) fields, arrays of numbers with
// a few components a cell (positions, velocities, gear5's derivatives), and any other state (per-beam flags, the
// neighbour list's pairs, the run's counters) as a visit function (core/state_archive). A checkpoint saves all
// of it and a continuation loads it, in the order declared; the per-cell fields are also what a distributed run
// moves with a cell (pack, unpack). Adding a field is one line where its owner declares its state.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "core/state_archive.hpp"

namespace frac {

class StateRegistry {
 public:
  // A per-cell field: `components` blocks of `cells` values (component c of cell k is coordinate c·cells + k),
  // stored in `values` at layout->index(coordinate) (a layout keeps the threads' parts apart), or at the
  // coordinate itself when `layout` is null. Saved under `name`, in coordinate order whatever the layout.
  struct CellField {
    std::string name;
    std::vector<double>* values = nullptr;
    std::size_t components = 1;
    const PartLayout* layout = nullptr;
  };

  explicit StateRegistry(std::size_t cells = 0) : cells_(cells) {}
  std::size_t cells() const { return cells_; }

  // Declares a field, or other state: visit(archive) names its arrays to the archive (saving or loading).
  void cell_field(CellField field);
  void other(std::function<void(StateArchive&)> visit);

  // Saves or loads everything, in the order declared.
  void visit(StateArchive& archive) const;

  const std::vector<CellField>& cell_fields() const { return fields_; }
  // The values of every per-cell field a cell carries, and its values copied out (in declaration order, each
  // field's components in turn) or in.
  std::size_t values_per_cell() const;
  void pack(std::size_t cell, double* out) const;
  void unpack(std::size_t cell, const double* in) const;

 private:
  struct Entry {
    std::size_t field = SIZE_MAX;  // index into fields_, or SIZE_MAX for `visit`
    std::function<void(StateArchive&)> visit;
  };
  void visit_field(const CellField& f, StateArchive& archive) const;
  std::size_t cells_;
  std::vector<CellField> fields_;
  std::vector<Entry> entries_;
};

}  // namespace frac
