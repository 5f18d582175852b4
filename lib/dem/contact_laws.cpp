#include "dem/contact_laws.hpp"

#include "core/error.hpp"

namespace frac::dem {

const ContactLawTable& contact_law_table() {
  static const ContactLawTable table{
      {"contact", [](const Material& m) { return contact_law(ElasticOverlap{m.grain_modulus * m.thickness}); },
       [](const Material&) { return std::array<double, 2>{}; }, true, false},
      {"damping", [](const Material& m) { return contact_law(NormalDamping{m.gamma_n}); },
       [](const Material& m) {
         return std::array<double, 2>{m.gamma_n, 0.0};
       }},
      {"friction",
       [](const Material& m) {
         return contact_law(CoulombFriction{m.gamma_t, m.friction});
       },
       [](const Material& m) {
         return std::array<double, 2>{0.0, m.gamma_t};
       }},
  };
  return table;
}

std::vector<std::string> read_contact_laws(Scene& scene, const ContactLawTable& table, bool contacts) {
  std::vector<std::string> on;
  for (const ContactLawRow& row : table) {
    const std::string key = "physics." + row.name;
    if (!row.switched) {
      if (contacts && row.default_on) on.push_back(row.name);
      continue;
    }
    if (!scene.flag(key, row.default_on)) continue;
    if (!contacts) scene.refuse(key, "a contact law: it needs physics.contacts = on");
    on.push_back(row.name);
  }
  return on;
}

std::array<double, 2> dashpot_rates(const ContactLawTable& table, std::span<const std::string> names,
                                    const Material& material) {
  std::array<double, 2> rates{};
  for (const ContactLawRow& row : table)
    if (std::find(names.begin(), names.end(), row.name) != names.end()) {
      const auto r = row.dashpot(material);
      rates[0] += r[0];
      rates[1] += r[1];
    }
  return rates;
}

ContactLaws make_contact_laws(const ContactLawTable& table, std::span<const std::string> names,
                              const Material& material) {
  for (const std::string& name : names) {
    bool known = false;
    for (const ContactLawRow& row : table) known = known || row.name == name;
    if (!known) throw UsageError("unknown contact law '" + name + "'");
  }
  ContactLaws out;
  for (const ContactLawRow& row : table) {
    for (const std::string& name : names) {
      if (name != row.name) continue;
      out.names.push_back(row.name);
      out.laws.push_back(row.make(material));
      break;
    }
  }
  return out;
}

void contact_kinematics(ContactList& c, const Bodies& bodies, std::span<const double> q, std::span<const double> v,
                        Range contacts) {
  const std::size_t n = bodies.n;
  const double* x = q.data();
  const double* y = x + n;
  const double* vx = v.data();
  const double* vy = vx + n;
  const double* w = vy + n;
  const double* mass = bodies.mass.data();
  for (std::size_t k = contacts.first; k < contacts.last; ++k) {
    const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
    const double nx = c.nx[k], ny = c.ny[k];
    // The velocities of i and j at R, v = v_c + ω ẑ×(R − c), and v_rel = v_j(R) − v_i(R) along n and t = ẑ × n.
    const double rix = c.rx[k] - x[i], riy = c.ry[k] - y[i], rjx = c.rx[k] - x[j], rjy = c.ry[k] - y[j];
    const double vrx = (vx[j] - w[j] * rjy) - (vx[i] - w[i] * riy);
    const double vry = (vy[j] + w[j] * rjx) - (vy[i] + w[i] * rix);
    c.vn[k] = vrx * nx + vry * ny;
    c.vt[k] = vry * nx - vrx * ny;
    c.m_eff[k] = mass[i] * mass[j] / (mass[i] + mass[j]);
    c.fn[k] = 0.0;
    c.ft[k] = 0.0;
  }
}

void apply_contact_laws(const ContactLaws& laws, ContactList& c, Range contacts) {
  for (std::size_t l = 0; l < laws.size(); ++l) laws.laws[l]->add(c, contacts, c.law_power[l].data());
}

std::vector<double> contact_forces(const ContactLaws& laws, ContactList& c, const Bodies& bodies,
                                   std::span<const double> q, std::span<const double> v) {
  c.set_laws(laws.size());
  as_team(c.size() > kMinParallelItems, [&] {
    const Range mine = this_thread_range(c.size());
    contact_kinematics(c, bodies, q, v, mine);
    apply_contact_laws(laws, c, mine);
  });
  std::vector<double> power(laws.size());
  for (std::size_t l = 0; l < laws.size(); ++l) power[l] = law_power(c, l);
  return power;
}

}  // namespace frac::dem
