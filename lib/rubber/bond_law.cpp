#include "rubber/bond_law.hpp"

#include <utility>

#include "core/error.hpp"

namespace frac::rubber {
namespace {

// Builds the alternative of Variant whose `name` matches, by walking the alternatives in order.
template <class Variant, std::size_t I = 0>
bool build(std::string_view name, const LawParams& p, Variant& out) {
  if constexpr (I < std::variant_size_v<Variant>) {
    using T = std::variant_alternative_t<I, Variant>;
    if (name == T::name) {
      out.template emplace<I>(p);
      return true;
    }
    return build<Variant, I + 1>(name, p, out);
  } else {
    return false;
  }
}

template <class Variant, std::size_t I = 0>
void names(std::vector<std::string>& out) {
  if constexpr (I < std::variant_size_v<Variant>) {
    out.emplace_back(std::variant_alternative_t<I, Variant>::name);
    names<Variant, I + 1>(out);
  }
}

template <class Variant>
Variant make(std::string_view name, const LawParams& p, std::string_view key) {
  Variant v{std::in_place_index<0>, p};
  if (!build(name, p, v)) {
    std::vector<std::string> list;
    names<Variant>(list);
    std::string all;
    for (const auto& n : list) all += (all.empty() ? "" : ", ") + n;
    throw UsageError(std::string(key) + ": unknown law '" + std::string(name) + "' (choose " + all + ")");
  }
  return v;
}

template <class Variant>
std::vector<std::string> list_names() {
  std::vector<std::string> out;
  names<Variant>(out);
  return out;
}

}  // namespace

PairLaw make_pair_law(std::string_view name, const LawParams& p, std::string_view key) {
  return make<PairLaw>(name, p, key);
}
CutoffLaw make_cutoff_law(std::string_view name, const LawParams& p, std::string_view key) {
  return make<CutoffLaw>(name, p, key);
}
AngleLaw make_angle_law(std::string_view name, const LawParams& p, std::string_view key) {
  return make<AngleLaw>(name, p, key);
}
ThreeBodyWeight make_three_body_weight(std::string_view name, const LawParams& p, std::string_view key) {
  return make<ThreeBodyWeight>(name, p, key);
}
std::vector<std::string> pair_law_names() { return list_names<PairLaw>(); }
std::vector<std::string> cutoff_law_names() { return list_names<CutoffLaw>(); }
std::vector<std::string> angle_law_names() { return list_names<AngleLaw>(); }
std::vector<std::string> three_body_weight_names() { return list_names<ThreeBodyWeight>(); }

BondLaw make_bond_law(const LawParams& p, std::string_view pair, std::string_view cutoff, std::string_view angle,
                      std::string_view weight) {
  return BondLaw{p, make_pair_law(pair, p), make_cutoff_law(cutoff, p), make_angle_law(angle, p),
                 make_three_body_weight(weight, p)};
}

}  // namespace frac::rubber
