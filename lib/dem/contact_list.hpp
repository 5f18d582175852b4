#pragma once
// The contacts between cells that the search found at one state (dem/contact_search), in pair order, with
// their geometry, the state the contact laws read (dem/contact_laws) and the forces they add; and the pass that
// adds the contacts' forces and torques to the cells. Every contact's force acts at one point R, equal and
// opposite on its two cells.
#include <cstdint>
#include <span>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/parallel.hpp"

namespace frac::dem {

struct ContactList {
  // Per contact, in entries [0, size()); the arrays may be longer (room kept from list to list).
  std::vector<std::int32_t> i, j;
  std::vector<double> rx, ry;  // application point R, m
  std::vector<double> nx, ny;  // unit normal from i to j
  std::vector<double> area;    // overlap area, m^2
  std::vector<double> inv_lc;  // 1/L_c = (1/r_i + 1/r_j)/2, m^-1
  // What the laws read (dem/contact_laws: contact_kinematics): the velocity of j relative to i at R along n
  // and t = ẑ × n (m/s), and the effective mass (kg).
  std::vector<double> vn, vt, m_eff;
  // The force on i summed over the laws that ran, along n (negative: repulsive) and t, N.
  std::vector<double> fn, ft;
  // The power of each law on each contact, W (law_power[l][k]), and its exact sum (core/exact_sum) over the
  // contacts of each thread of the team that filled the list (power_part[l][t]), merged after the team: the
  // same value whatever the thread count, the order of the contacts or, on several ranks, their split.
  std::vector<std::vector<double>> law_power;
  std::vector<std::vector<ExactSum>> power_part;
  std::size_t size() const { return count_; }  // (set by ContactSearch::find_end)
  // Room for `count` contacts (never shrinks; the size is unchanged).
  void reserve(std::size_t count);
  std::size_t room() const { return i.size(); }
  // Room for the powers of `laws` laws, and their parts for teams of up to `threads` threads.
  void set_laws(std::size_t laws);
  void reserve_power_parts(std::size_t threads);
  // The geometry of `from`'s first `count` entries copied to entries [to, to + count) (the search's fill).
  void copy_entries(const ContactList& from, std::size_t count, std::size_t to);
  // Diagnostics of the last search.
  std::int64_t candidate_pairs = 0;  // pairs whose bounding circles overlap
  std::int64_t enclosed = 0;         // overlaps without a contact line (one polygon inside another)
  std::int64_t multi_crossing = 0;   // more than 2 crossings (a corner poked through)
  // The contacts that thread t of the team that filled the list wrote, [block[t].first, block[t].last), for
  // the `blocks` threads of that team (the search's last step sets them): the contact laws run on these on
  // the same team, each thread on the contacts it wrote, with no barrier between.
  std::vector<Range> block;
  std::size_t blocks = 0;
  // touch[t·blocks + u]: the entries of block t from the first to the last that touches a cell of thread u's
  // part of the cells (static_range of the cells over `blocks` threads); empty if none: a thread adding the
  // forces onto its cells reads only those of the other threads' blocks (set by the search).
  std::vector<Range> touch;
  // This thread's contacts: its block when the team that filled the list is the calling team, else its
  // static part.
  Range mine() const;

 private:
  friend class ContactSearch;
  std::size_t count_ = 0;
};

// Law l's power summed over the list (exactly rounded).
double law_power(const ContactList& c, std::size_t law);
// In a phase after every law's, thread t of the team that filled the list: law l's power over its block of the
// first `count` contacts, into power_part[l][t]. After the team, law_power_of_parts merges the team's parts: the
// same value as law_power.
void law_power_part(ContactList& c, std::size_t law, std::size_t count, std::size_t t);
double law_power_of_parts(const ContactList& c, std::size_t law, std::size_t threads);

// Adds the contacts' forces, F = fn·n + ft·t on i and −F on j at R, and their torques about the centroids to the
// cells' forces f (layout of q: fx, fy, torque), each cell its contacts in contact order. q: positions.
void add_contact_forces(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f);
// The same for the first `count` contacts of the list and the cells in `cells` only (a team's part: each
// thread its cells, the same bits as the whole pass).
void add_contact_forces(const ContactList& c, std::size_t count, std::size_t n, std::span<const double> q,
                        std::span<double> f, Range cells);
// The same, thread t's part of a phase on a team of nt, the team that filled the list (in a phase after every
// law's): onto t's part of the cells, reading its own block and, of the others, only the entries that touch its
// cells (ContactList::touch), in block order.
void add_contact_forces_of_team(const ContactList& c, std::size_t n, std::span<const double> q, std::span<double> f,
                                std::size_t t, std::size_t nt);

}  // namespace frac::dem
