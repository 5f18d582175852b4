#include "core/state_registry.hpp"

#include <cstdint>

namespace frac {

void StateRegistry::cell_field(CellField field) {
  entries_.push_back({fields_.size(), {}});
  fields_.push_back(std::move(field));
}

void StateRegistry::other(std::function<void(StateArchive&)> visit) {
  entries_.push_back({SIZE_MAX, std::move(visit)});
}

void StateRegistry::visit(StateArchive& archive) const {
  for (const Entry& e : entries_) {
    if (e.field == SIZE_MAX)
      e.visit(archive);
    else
      visit_field(fields_[e.field], archive);
  }
}

void StateRegistry::visit_field(const CellField& f, StateArchive& archive) const {
  const std::size_t n = f.components * cells_;
  if (!f.layout) {
    archive.array(f.name, *f.values, n);
    return;
  }
  // (In coordinate order: the layout of the threads' parts depends on the thread count.)
  std::vector<double> ordered(n);
  if (!archive.loading())
    for (std::size_t i = 0; i < n; ++i) ordered[i] = (*f.values)[f.layout->index(i)];
  archive.array(f.name, ordered, n);
  if (archive.loading())
    for (std::size_t i = 0; i < n; ++i) (*f.values)[f.layout->index(i)] = ordered[i];
}

std::size_t StateRegistry::values_per_cell() const {
  std::size_t count = 0;
  for (const CellField& f : fields_) count += f.components;
  return count;
}

void StateRegistry::pack(std::size_t cell, double* out) const {
  for (const CellField& f : fields_)
    for (std::size_t c = 0; c < f.components; ++c) {
      const std::size_t i = c * cells_ + cell;
      *out++ = (*f.values)[f.layout ? f.layout->index(i) : i];
    }
}

void StateRegistry::unpack(std::size_t cell, const double* in) const {
  for (const CellField& f : fields_)
    for (std::size_t c = 0; c < f.components; ++c) {
      const std::size_t i = c * cells_ + cell;
      (*f.values)[f.layout ? f.layout->index(i) : i] = *in++;
    }
}

}  // namespace frac
