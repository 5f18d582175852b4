#pragma once
// All beams of a sample: per-beam data in arrays, the intact ones in an active table (a broken beam is never
// tested again), the broken ones moved to a table of their own; the force loop, the energy, and the breaking pass.
#include <cstdint>
#include <span>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/state_archive.hpp"
#include "dem/beam.hpp"
#include "dem/bodies.hpp"
#include "mesh/cell_mesh.hpp"

namespace frac::dem {

struct BeamBreak {
  std::int64_t beam;
  int mode;       // 1 stretching, 2 bending
  double energy;  // elastic energy it held, J
};

// The part of a beam's response a loop over the beams reads (Beams' loops compute only that).
enum class BeamResponsePart { forces, energy, strain };

class Beams {
 public:
  Beams() = default;
  Beams(const mesh::CellMesh& mesh, const Material& material);

  std::size_t size() const { return intact_.size(); }
  std::size_t intact_count() const { return active_.size() - broken_in_active_; }
  std::span<const std::uint8_t> intact() const { return intact_; }
  // Beam b's cells and constants (a search: not for loops).
  std::int32_t cell_i(std::size_t b) const { return find(b).table->i[find(b).k]; }
  std::int32_t cell_j(std::size_t b) const { return find(b).table->j[find(b).k]; }
  BeamStiffness stiffness(std::size_t b) const { return find(b).stiffness(); }
  double rest_length(std::size_t b) const { return find(b).table->l0[find(b).k]; }

  // Adds the beam forces and moments at state q into f (same layout as q: fx, fy, torque). (Their power
  // is not bookkept as work: the beam law derives from an energy, which the ledger holds.)
  void add_forces(std::span<const double> q, std::span<double> f) const;
  // The same forces written into f, replacing what is there (the same bits as add_forces onto zeros). Both
  // run on threads of their own: call them outside a parallel region.
  void set_forces(std::span<const double> q, std::span<double> f) const;
  // The same as two phases of a step (core/phases), thread t's part of a team of nt: beam_pass, each beam's
  // force at q (t's part of the beams); in a later phase, gather, each of t's cells its beams' forces, onto f
  // (add) or into it.
  void beam_pass(std::span<const double> q, std::size_t t, std::size_t nt) const;
  void gather(std::span<double> f, bool add, std::size_t t, std::size_t nt) const;
  // Elastic energy of the intact beams at q, J.
  double energy(std::span<const double> q) const;
  // Strain of every beam at q (broken beams too, for pictures).
  void strains(std::span<const double> q, std::span<double> out) const;
  // Breaks, for good, every intact beam that satisfies the rule at q; appends them to `broken`.
  void break_beams(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken);
  // The same as phases of a step (core/phases): bind_breaking before each run (outside the team); "beams:
  // breaking verdicts" (each thread its part of the intact beams, in blocks), then "beams: break" (serial: the
  // beams found, in list order, marked broken and appended to `broken`). The phases call this object: take
  // them once it is in place.
  void bind_breaking(std::span<const double> q, double t_eps, double t_theta, std::vector<BeamBreak>& broken);
  Phases breaking_phases();
  // Breaks one beam (tests, and a scene's explicit cut).
  void remove(std::size_t b);
  // Marks every beam broken (a scene without beams: no cohesion, every cell its own fragment).
  void remove_all();
  // The state a continuation needs (core/state_archive): which beams are intact, and the active list.
  void visit_state(StateArchive& archive);
  // Broken beams leave the active list in batches, not at every step a beam breaks (a serial pass over the
  // list, whose entries the other threads hold in their caches): until then they stay in it, marked broken
  // (intact()), their responses zero and uncomputed; the list is compacted once more than one entry in
  // kCompactEvery is such a beam.
  static constexpr std::size_t kCompactEvery = 32;

 private:
  // add_forces (add) or set_forces.
  void forces(std::span<const double> q, std::span<double> f, bool add) const;
  // Per-beam data in arrays, entry k for beam beam[k], in beam order: the intact beams (active_, and the broken
  // ones not yet compacted out of it) and the broken ones (retired_). Each beam is in one of the two, so that a
  // loop over the intact ones reads their constants in sequence, and no constant is held twice.
  struct BeamTable {
    std::vector<std::int32_t> beam, i, j;
    std::vector<double> e0x, e0y, l0, alpha, beta, delta;
    std::size_t size() const { return beam.size(); }
    void resize(std::size_t n);
    void copy_entry(std::size_t to, const BeamTable& source, std::size_t from);  // entry `to` := source's `from`
    void erase(std::size_t k);                                                   // the entries after k move up by one
    void push_back(const BeamTable& source, std::size_t from);
    // The entries of a and b (each in beam order, no beam in both) merged in beam order; in(a, k): whether a's
    // entry k goes in.
    template <class Keep>
    static BeamTable merged(const BeamTable& a, const BeamTable& b, Keep&& in);
  };
  struct Entry {
    const BeamTable* table;
    std::size_t k;
    BeamStiffness stiffness() const { return {table->alpha[k], table->beta[k], table->delta[k]}; }
  };
  Entry find(std::size_t b) const;  // where beam b is (b < size())
  BeamResponse response(const BeamTable& t, std::size_t k, std::span<const double> q) const;
  // use(k, b, r) with beam_response's values r of beam b = t.beam[k], for k in [first, last), in order, where r
  // holds part P (the other fields are zero): in blocks, the beams' states gathered into arrays, then the
  // branch-free formula of a beam near its reference orientation as a vector loop over them (no library call,
  // no branch, no indirect load), then beam_response, one at a time, for the beams it does not cover (rotated
  // by more than π/8: the spinning fragments of an explosion). (beams.cpp only.)
  // A broken beam still in the active table (between compactions) gets a zero response, uncomputed, unless
  // `broken_too`.
  template <BeamResponsePart P, class Use>
  void each_response(std::span<const double> q, const BeamTable& t, std::size_t first, std::size_t last, Use&& use,
                     bool broken_too = false) const;
  // on_block(start, count, block) for blocks of the entries [first, last) of t, in order: the states at q of
  // entries start .. start + count − 1 gathered into the block's arrays, its constants pointing into t
  // (beams.cpp's ResponseBlock).
  template <class OnBlock>
  void each_block(std::span<const double> q, const BeamTable& t, std::size_t first, std::size_t last,
                  OnBlock&& on_block) const;
  std::size_t n_ = 0;  // cells
  BeamTable active_, retired_;
  std::vector<std::uint8_t> intact_;
  struct BeamForce {
    double fx, fy;
    double torque[2];  // on cell i, on cell j
  };
  mutable std::vector<BeamForce> force_;  // per beam (indexed by beam), filled in parallel for the intact ones
  // The intact beams of each cell in beam order (beams_of_[cell_start_[c] .. + cell_count_[c])), with
  // which end the cell is (0: i, 1: j; the force on it has the sign 1 − 2·end): each cell gathers its
  // beams' forces in the order a loop over the beams would add them (the same bits), so cells can be
  // summed in parallel. A broken beam is taken out of its two cells' lists.
  struct CellBeam {
    std::int32_t beam;
    std::int32_t end;
  };
  void index_cells();
  void unindex(const BeamTable& t, std::size_t k);  // takes entry k's beam out of its cells' lists
  std::vector<std::int32_t> cell_start_, cell_count_;
  std::vector<CellBeam> beams_of_;
  mutable std::vector<ExactSum> energy_parts_;  // energy()'s sums, a thread each
  struct Verdict {
    int mode;       // breaking_mode's
    double energy;  // elastic energy, J, when it breaks
  };
  // The breaking pass: each thread lists the entries of its part of the active list that break, in order.
  struct Breaking {
    std::size_t entry;
    Verdict verdict;
  };
  TeamSlots<std::vector<Breaking>> breaking_;
  // The bodies of the breaking phases, at the bound state; thread t of a team of nt.
  void find_breaks(std::size_t t, std::size_t nt);
  void apply_breaks(std::size_t nt);
  struct BreakingState {
    std::span<const double> q;
    double t_eps = 0, t_theta = 0;
    std::vector<BeamBreak>* broken = nullptr;
  } breaking_state_;
  std::size_t broken_in_active_ = 0;
  void compact_active();  // the broken beams of active_ moved to retired_
};

}  // namespace frac::dem
