#include "analysis/fragments.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <numeric>
#include <string>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace frac::analysis {

std::size_t Fragments::count_at_least(std::int64_t min_cells) const {
  return static_cast<std::size_t>(
      std::count_if(cell_count.begin(), cell_count.end(), [&](std::int64_t c) { return c >= min_cells; }));
}

std::vector<double> Fragments::masses_at_least(std::int64_t min_cells) const {
  std::vector<double> out;
  out.reserve(count_at_least(min_cells));
  for (std::size_t f = 0; f < mass.size(); ++f)
    if (cell_count[f] >= min_cells) out.push_back(mass[f]);
  return out;
}

double Fragments::mean_cell_mass() const {
  return cell_fragment.empty() ? 0.0 : total_mass / static_cast<double>(cell_fragment.size());
}

void UnionFind::reset(std::size_t n) {
  parent_.resize(n);
  size_.assign(n, 1);
  std::iota(parent_.begin(), parent_.end(), std::int64_t{0});
}

void UnionFind::unite(std::int64_t a, std::int64_t b) {
  a = find(a);
  b = find(b);
  if (a == b) return;
  if (size_[a] < size_[b]) std::swap(a, b);
  parent_[b] = a;
  size_[a] += size_[b];
}

namespace {

// Compensated sum (Neumaier): the rounding error of every addition is kept in `c`, so a sum of positive
// terms comes out correctly rounded but for cases within ~n^2 eps^2 of a rounding boundary, and does
// not depend on the order of the terms. Makes fragment masses independent of the cell numbering.
struct Sum {
  double s = 0.0, c = 0.0;
  void add(double x) {
    const double t = s + x;
    c += std::abs(s) >= std::abs(x) ? (s - t) + x : (x - t) + s;
    s = t;
  }
  double value() const { return s + c; }
};

void check_size(const char* what, std::size_t got, std::size_t want, const char* of) {
  if (got != want)
    throw InputError(std::string(what) + ": " + std::to_string(got) + " values, expected " + std::to_string(want) +
                     " (" + of + ")");
}

void check_finite(const char* what, std::span<const double> v, double min) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]) || v[k] < min)
      throw InputError(std::string(what) + ": value " + std::to_string(v[k]) + " at index " + std::to_string(k) +
                       (min == 0.0 ? " (must be finite and non-negative)" : " (must be finite)"));
}

void check_positive(const char* what, std::span<const double> v) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]) || !(v[k] > 0.0))
      throw InputError(std::string(what) + ": value " + std::to_string(v[k]) + " at index " + std::to_string(k) +
                       " (must be positive and finite)");
}

void check_beams(std::span<const std::int64_t> beam, std::span<const std::uint8_t> intact, std::size_t n) {
  if (beam.size() % 2 != 0) throw InputError("beams: " + std::to_string(beam.size()) + " indices, not pairs");
  check_size("beam intact flags", intact.size(), beam.size() / 2, "one per beam");
  for (std::size_t k = 0; k < beam.size(); ++k)
    if (beam[k] < 0 || static_cast<std::size_t>(beam[k]) >= n)
      throw InputError("beams: beam " + std::to_string(k / 2) + " joins cell " + std::to_string(beam[k]) +
                       ", outside 0.." + std::to_string(static_cast<long long>(n) - 1));
}

}  // namespace

void check_state(const CellState& s) {
  const std::size_t n = s.mass.size();
  check_size("inertia", s.inertia.size(), n, "one per cell");
  check_size("position", s.position.size(), 2 * n, "two per cell");
  check_size("velocity", s.velocity.size(), 2 * n, "two per cell");
  check_size("angular velocity", s.angular_velocity.size(), n, "one per cell");
  check_positive("mass", s.mass);
  check_finite("inertia", s.inertia, 0.0);
  check_finite("position", s.position, -HUGE_VAL);
  check_finite("velocity", s.velocity, -HUGE_VAL);
  check_finite("angular velocity", s.angular_velocity, -HUGE_VAL);
  check_beams(s.beam, s.intact, n);
}

namespace {

// Provisional ids in order of each fragment's smallest cell (cells visited in increasing index): fills
// out.cell_fragment and out.total_mass, `label` (by root), each fragment's first cell and mass sum.
void label_fragments(const CellState& s, UnionFind& uf, std::vector<std::int64_t>& label,
                     std::vector<std::int64_t>& first, std::vector<Sum>& sum, Fragments& out) {
  const std::size_t n = s.mass.size();
  out.cell_fragment.resize(n);
  std::size_t roots = 0;
  for (std::size_t i = 0; i < n; ++i) roots += uf.find(static_cast<std::int64_t>(i)) == static_cast<std::int64_t>(i);
  first.reserve(roots);  // the loop below then never allocates
  sum.reserve(roots);
  Sum total;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = uf.find(static_cast<std::int64_t>(i));
    if (label[r] < 0) {
      label[r] = static_cast<std::int64_t>(first.size());
      first.push_back(static_cast<std::int64_t>(i));
      sum.emplace_back();
    }
    out.cell_fragment[i] = label[r];
    sum[label[r]].add(s.mass[i]);
    total.add(s.mass[i]);
  }
  out.total_mass = total.value();
}

// Final ids: mass decreasing, ties by smallest cell, which is by provisional id (ids were given in
// increasing order of the smallest cell). Sorted as (mass, id) pairs: no indirection in the compares.
// `rank` is reused storage (provisional id -> final id); `sum` is released once read.
void order_by_mass(std::vector<Sum>& sum, const std::vector<std::int64_t>& first, std::vector<std::int64_t>& rank,
                   Fragments& out) {
  const std::size_t f = first.size();
  struct Key {
    double mass;
    std::int64_t id;
  };
  std::vector<Key> order(f);
  for (std::size_t j = 0; j < f; ++j) order[j] = {sum[j].value(), static_cast<std::int64_t>(j)};
  std::vector<Sum>().swap(sum);
  std::sort(order.begin(), order.end(),
            [](const Key& a, const Key& c) { return a.mass != c.mass ? a.mass > c.mass : a.id < c.id; });
  out.mass.resize(f);
  out.first_cell.resize(f);
  for (std::size_t j = 0; j < f; ++j) {
    rank[order[j].id] = static_cast<std::int64_t>(j);
    out.mass[j] = order[j].mass;
    out.first_cell[j] = first[order[j].id];
  }
  std::vector<Key>().swap(order);
  for (auto& id : out.cell_fragment) id = rank[id];
}

// Centre of mass and its velocity (mass-weighted sums in increasing cell index), translational kinetic
// energy, and kinetic energy in each fragment's centre-of-mass frame.
void add_motion(const CellState& s, Fragments& out) {
  const std::size_t n = s.mass.size();
  const std::size_t f = out.mass.size();
  out.cell_count.assign(f, 0);
  out.center_of_mass.assign(2 * f, 0.0);
  out.velocity.assign(2 * f, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = out.cell_fragment[i];
    const double m = s.mass[i];
    ++out.cell_count[id];
    out.center_of_mass[2 * id] += m * s.position[2 * i];
    out.center_of_mass[2 * id + 1] += m * s.position[2 * i + 1];
    out.velocity[2 * id] += m * s.velocity[2 * i];
    out.velocity[2 * id + 1] += m * s.velocity[2 * i + 1];
  }
  out.kinetic_energy_translational.resize(f);
  for (std::size_t j = 0; j < f; ++j) {
    const double m = out.mass[j];
    const double inv = 1.0 / m;
    for (int c = 0; c < 2; ++c) {
      out.center_of_mass[2 * j + c] *= inv;
      out.velocity[2 * j + c] *= inv;
    }
    const double vx = out.velocity[2 * j], vy = out.velocity[2 * j + 1];
    out.kinetic_energy_translational[j] = 0.5 * m * (vx * vx + vy * vy);
  }

  // Kinetic energy in each fragment's centre-of-mass frame.
  out.kinetic_energy_rotational.assign(f, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = out.cell_fragment[i];
    const double dx = s.velocity[2 * i] - out.velocity[2 * id];
    const double dy = s.velocity[2 * i + 1] - out.velocity[2 * id + 1];
    const double w = s.angular_velocity[i];
    out.kinetic_energy_rotational[id] += 0.5 * (s.mass[i] * (dx * dx + dy * dy) + s.inertia[i] * w * w);
  }
}

}  // namespace

Fragments find_fragments(const CellState& s) try {
  check_state(s);
  const std::size_t n = s.mass.size();
  const std::size_t b = s.intact.size();

  UnionFind uf(n);
  for (std::size_t k = 0; k < b; ++k)
    if (s.intact[k]) uf.unite(s.beam[2 * k], s.beam[2 * k + 1]);

  Fragments out;
  std::vector<std::int64_t> label(n, -1);  // by root
  std::vector<std::int64_t> first;
  std::vector<Sum> sum;
  label_fragments(s, uf, label, first, sum, out);
  order_by_mass(sum, first, label, out);
  add_motion(s, out);
  return out;
} catch (const std::bad_alloc&) {
  throw out_of_memory("the fragments of " + std::to_string(s.mass.size()) + " cells");
}

FragmentCount FragmentCounter::operator()(std::span<const double> mass, std::span<const std::int64_t> beam,
                                          std::span<const std::uint8_t> intact, std::int64_t min_cells) {
  const std::size_t n = mass.size();
  check_beams(beam, intact, n);
  uf_.reset(n);
  for (std::size_t k = 0; k < intact.size(); ++k)
    if (intact[k]) uf_.unite(beam[2 * k], beam[2 * k + 1]);
  // Same compensated sums as find_fragments, so a frame's largest mass matches its /fragments/mass[0].
  root_mass_.assign(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(uf_.find(static_cast<std::int64_t>(i)));
    Sum acc{root_mass_[2 * r], root_mass_[2 * r + 1]};
    acc.add(mass[i]);
    root_mass_[2 * r] = acc.s;
    root_mass_[2 * r + 1] = acc.c;
  }
  FragmentCount out;
  for (std::size_t i = 0; i < n; ++i) {
    if (uf_.find(static_cast<std::int64_t>(i)) != static_cast<std::int64_t>(i)) continue;
    if (uf_.set_size(static_cast<std::int64_t>(i)) >= min_cells) ++out.count;
    out.largest_mass = std::max(out.largest_mass, Sum{root_mass_[2 * i], root_mass_[2 * i + 1]}.value());
  }
  return out;
}

}  // namespace frac::analysis

namespace frac::analysis {

LogHistogram mass_histogram(const Fragments& f, std::int64_t min_cells, double bins_per_decade) {
  if (!(bins_per_decade > 0) || !std::isfinite(bins_per_decade))
    throw UsageError("bins per decade: must be positive, got " + std::to_string(bins_per_decade));
  const auto masses = f.masses_at_least(min_cells);
  if (masses.empty()) {
    LogHistogram h;
    h.bins_per_decade = bins_per_decade;
    return h;
  }
  return log_histogram(masses, {bins_per_decade, false, f.mean_cell_mass()});
}

}  // namespace frac::analysis
