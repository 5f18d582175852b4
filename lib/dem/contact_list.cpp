#include "dem/contact_list.hpp"

#include <algorithm>

namespace frac::dem {

void ContactList::reserve(std::size_t count) {
  if (count <= room()) return;
  for (auto* a : {&i, &j}) a->resize(count);
  for (auto* a : {&rx, &ry, &nx, &ny, &area, &inv_lc, &vn, &vt, &m_eff, &fn, &ft}) a->resize(count);
  for (auto& a : law_power) a.resize(count);
}

void ContactList::set_laws(std::size_t laws) {
  law_power.resize(laws);
  power_part.resize(laws);
  for (auto& a : law_power) a.resize(room());
}

void ContactList::reserve_power_parts(std::size_t threads) {
  for (auto& a : power_part)
    if (a.size() < threads) a.resize(threads);
}

void ContactList::copy_entries(const ContactList& from, std::size_t count, std::size_t to) {
  // (The search's fill: the geometry only. The laws' state and forces are set after it.)
  const auto copy = [&](const auto& source, auto& target) {
    std::copy(source.begin(), source.begin() + static_cast<std::ptrdiff_t>(count),
              target.begin() + static_cast<std::ptrdiff_t>(to));
  };
  copy(from.i, i);
  copy(from.j, j);
  copy(from.rx, rx);
  copy(from.ry, ry);
  copy(from.nx, nx);
  copy(from.ny, ny);
  copy(from.area, area);
  copy(from.inv_lc, inv_lc);
}

Range ContactList::mine() const {
  if (blocks == static_cast<std::size_t>(thread_count())) return block[static_cast<std::size_t>(thread_index())];
  return this_thread_range(size());
}

double law_power(const ContactList& c, std::size_t law) {
  ExactSum sum;
  for (std::size_t k = 0; k < c.size(); ++k) sum.add(c.law_power[law][k]);
  return sum.value();
}

void law_power_part(ContactList& c, std::size_t law, std::size_t count, std::size_t t) {
  const Range mine = c.block[t];
  ExactSum sum;
  for (std::size_t k = mine.first; k < std::min(mine.last, count); ++k) sum.add(c.law_power[law][k]);
  c.power_part[law][t] = sum;
}

double law_power_of_parts(const ContactList& c, std::size_t law, std::size_t threads) {
  return sum_of(std::span(c.power_part[law]).first(threads));
}

void add_contact_forces(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f) {
  add_contact_forces(c, c.size(), n, q, f, Range{0, n});
}

namespace {
// The contacts [first_contact, last_contact) onto the cells of `cells`, in contact order.
void add_contact_range(const ContactList& c, std::size_t first_contact, std::size_t last_contact, std::size_t n,
                       std::span<const double> q, std::span<double> f, Range cells) {
  // One pass over the list in contact order, adding to the cells of `cells` only: each cell receives its
  // contacts in contact order, the same additions in the same order whatever the split. (Every thread reads
  // the whole list but writes, and reads the positions of, its own cells only. A per-cell gather was slower.)
  // The torques about c_i and c_j: τ_i = r_i × F, τ_j = −r_j × F, r = R − c.
  const double* x = q.data();
  const double* y = x + n;
  double* fxa = f.data();
  double* fya = fxa + n;
  double* tz = fya + n;
  const double *fn = c.fn.data(), *ft = c.ft.data(), *nx = c.nx.data(), *ny = c.ny.data();
  const std::int32_t *ci = c.i.data(), *cj = c.j.data();
  const double *rx = c.rx.data(), *ry = c.ry.data();
  const std::size_t first = cells.first, width = cells.last - cells.first;
  for (std::size_t k = first_contact; k < last_contact; ++k) {
    const auto i = static_cast<std::size_t>(ci[k]), j = static_cast<std::size_t>(cj[k]);
    const double fx = fn[k] * nx[k] - ft[k] * ny[k], fy = fn[k] * ny[k] + ft[k] * nx[k];  // (t = ẑ × n)
    if (i - first < width) {  // (unsigned: also false below `first`)
      fxa[i] += fx;
      fya[i] += fy;
      tz[i] += (rx[k] - x[i]) * fy - (ry[k] - y[i]) * fx;
    }
    if (j - first < width) {
      fxa[j] -= fx;
      fya[j] -= fy;
      tz[j] -= (rx[k] - x[j]) * fy - (ry[k] - y[j]) * fx;
    }
  }
}

}  // namespace

void add_contact_forces_of_team(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f,
                                std::size_t t, std::size_t nt) {
  const Range cells = static_range(n, t, nt);
  for (std::size_t b = 0; b < nt; ++b) {
    const Range r = b == t ? c.block[b] : c.touch[b * nt + t];
    add_contact_range(c, r.first, r.last, n, q, f, cells);
  }
}

void add_contact_forces(const ContactList& c, std::size_t count, std::size_t n, std::span<const double> q,
                        std::span<double> f, Range cells) {
  add_contact_range(c, 0, count, n, q, f, cells);
}

}  // namespace frac::dem
