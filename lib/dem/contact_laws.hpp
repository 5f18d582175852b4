#pragma once
// The contact force laws (physics/polygon-dem.md §3) as evaluators: each law a plain struct, built from the
// material, whose call gives its force on cell i at one contact from what it reads of that contact
// (ContactState); j receives the opposite, both at the contact point R, so momentum and angular momentum are
// conserved exactly. One loop, written once (ContactLawLoop), runs a law over a range of contacts, adds its
// force to each contact's normal and tangential force and writes the power it delivers. A scene's laws run in
// the order of the table's rows:
//   contact   ElasticOverlap   F_n = −Y·h·A/L_c                          (negative: repulsive)
//   damping   NormalDamping    F_n = m_eff·γ_N·v_n                       (v_n < 0 while approaching)
//   friction  CoulombFriction  F_t = sign(v_t)·min(m_eff·γ_T·|v_t|, μ·|F_n|), F_n of the laws before it
// A new law is one struct and one row of a table (contact_law_table() or a caller's own): a scene switches it on
// by its row's key (physics.<name> = on), and the row gives the dashpot rates it adds to the stable time step.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_list.hpp"
#include "dem/material.hpp"

namespace frac::dem {

// What a law reads of one contact.
struct ContactState {
  double area;    // overlap area A, m^2
  double inv_lc;  // 1/L_c = (1/r_i + 1/r_j)/2, m^-1
  double vn, vt;  // velocity of j relative to i at R along n and t = ẑ × n, m/s
  double m_eff;   // m_i·m_j/(m_i + m_j), kg
  double fn;      // normal force on i of the laws before this one, N
};

// A law's force on i at one contact, along n and t.
struct LawForce {
  double normal = 0, tangential = 0;
};

struct ElasticOverlap {
  double yh;  // Y·h, N/m
  LawForce operator()(const ContactState& s) const { return {-yh * s.area * s.inv_lc, 0.0}; }
};

struct NormalDamping {
  double gamma_n;  // s^-1
  LawForce operator()(const ContactState& s) const { return {s.m_eff * gamma_n * s.vn, 0.0}; }
};

struct CoulombFriction {
  double gamma_t, mu;  // s^-1, 1
  LawForce operator()(const ContactState& s) const {
    return {0.0, std::copysign(std::min(s.m_eff * gamma_t * std::abs(s.vt), mu * std::abs(s.fn)), s.vt)};
  }
};

// A law over the contacts: adds its force at contacts [first, last) of `c` to c.fn and c.ft, and writes the
// power it delivers to the bodies at each, F·(v_i(R) − v_j(R)), into power[k] (W).
class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  virtual void add(ContactList& c, Range contacts, double* power) const = 0;
};

// The loop, for any law L with `LawForce L::operator()(const ContactState&) const`.
template <class Law>
class ContactLawLoop final : public ContactLaw {
 public:
  explicit ContactLawLoop(Law law) : law_(law) {}
  void add(ContactList& c, Range contacts, double* power) const override {
    for (std::size_t k = contacts.first; k < contacts.last; ++k) {
      const ContactState s{c.area[k], c.inv_lc[k], c.vn[k], c.vt[k], c.m_eff[k], c.fn[k]};
      const LawForce f = law_(s);
      c.fn[k] += f.normal;
      c.ft[k] += f.tangential;
      power[k] = -(f.normal * s.vn + f.tangential * s.vt);
    }
  }

 private:
  Law law_;
};

template <class Law>
std::unique_ptr<ContactLaw> contact_law(Law law) {
  return std::make_unique<ContactLawLoop<Law>>(law);
}

// A row of a table of laws: the name the scene's switch (physics.<name>) and the energy ledger use; whether it is
// on by default (the elastic overlap: on whenever contacts are, and no switch of its own); the law built from the
// material; and the viscous rates it adds along the normal and the tangent (s^-1), which bound the time step.
struct ContactLawRow {
  std::string name;
  std::function<std::unique_ptr<ContactLaw>(const Material&)> make;
  std::function<std::array<double, 2>(const Material&)> dashpot = [](const Material&) {
    return std::array<double, 2>{};
  };
  bool default_on = false;
  bool switched = true;  // false: on with the contacts (physics.contacts), no key of its own
};
using ContactLawTable = std::vector<ContactLawRow>;
// The laws of the paper: contact, damping, friction.
const ContactLawTable& contact_law_table();
// The laws a scene switches on ([physics]: physics.contacts, then each row's physics.<name>), in the table's order;
// UsageError naming the key of a law switched on without contacts.
std::vector<std::string> read_contact_laws(Scene& scene, const ContactLawTable& table, bool contacts);
// The viscous rates (normal, tangential) the laws `names` of `table` add up to, s^-1.
std::array<double, 2> dashpot_rates(const ContactLawTable& table, std::span<const std::string> names,
                                    const Material& material);

// A scene's laws, in the table's order, with their names.
struct ContactLaws {
  std::vector<std::string> names;
  std::vector<std::unique_ptr<ContactLaw>> laws;
  std::size_t size() const { return laws.size(); }
};
// The laws `names` of `table` (UsageError for a name the table lacks), ordered as the table's rows.
ContactLaws make_contact_laws(const ContactLawTable& table, std::span<const std::string> names,
                              const Material& material);

// The state every law reads, at contacts [first, last): the relative velocity at R along n and t from (q, v), the
// effective mass; the contacts' forces set to zero.
void contact_kinematics(ContactList& c, const Bodies& bodies, std::span<const double> q, std::span<const double> v,
                        Range contacts);
// The laws, in order, at contacts [first, last): law l writes its power into c.law_power[l].
void apply_contact_laws(const ContactLaws& laws, ContactList& c, Range contacts);
// Both, on threads of their own (outside a parallel region), over the whole list; returns each law's power
// summed over the list (W), the same bits whatever the thread count.
std::vector<double> contact_forces(const ContactLaws& laws, ContactList& c, const Bodies& bodies,
                                   std::span<const double> q, std::span<const double> v);

}  // namespace frac::dem
