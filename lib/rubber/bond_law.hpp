#pragma once
// The bond law of Marder's rubber lattice (physics/rubber-lattice.md §3), as small evaluators:
//
//   U = Σ_i Σ_{j∈n(i)} f(u_ij)  +  Σ_i Σ_{j≠k∈n(i)} h(u_ij) h(u_ik) g(u_ij·u_ik)
//
//   f(u)  pair term                 (PairMarder: eq. 31 corrected; PairMarderC1: the C¹ variant of §3;
//                                    PairMarderSoft: fades out over the cut-off width, softening)
//   h(u)  cut-off, fails the bond   (CutoffFermi: eq. 32 with its own width; CutoffSmoothstep: compact
//                                    support, softening; CutoffNone: h ≡ 1)
//   g(X)  three-body term           (AngleMarder: eq. 33, −(B/27)(X + 2Δ²)²)
//
// Each evaluator is a plain struct with a `name` (its scene key value) and an operator() that returns
// the value and the derivative; the force loop (rubber/forces) is written once over all of them. A new
// law is one new struct here plus its type in the variant below: the scene key [law] pair / cutoff /
// angle then accepts its name, and the force loop needs no edit.
//
// Lengths in metres (SI), energies in joules. u_c is passed per call so that a bond may carry its own
// cut-off (toughening).
#include <cmath>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace frac::rubber {

// Value and derivative.
struct VD {
  double v, d;
};

struct LawParams {
  double spacing = 1;             // Δ (m)
  double A = 1, B = 1.5 * 9 / 8;  // J m^-2 and J m^-4: A = m a/Δ², B = 9 m a b/(8Δ⁴) (mooney_rivlin.hpp)
  double short_width = 0.1;       // u_s (m): width of branch 1 of f (short, repulsive bonds)
  double cutoff = 4;              // u_c (m): separation at which a bond fails
  double cutoff_width = 0.1;      // u_s,h (m): width of the Fermi cut-off h (a separate parameter, §3)
};

// ------------------------------------------------------------------------------------------ f(u)
// f(u) = (A/6)(u²−Δ²)(u−Δ)/u_s + (B/9)(u²−Δ²)² + K0   u < Δ+u_s      (branch 1: stress-free at Δ)
//      = (A/6)(u²−Δ²)          + (B/9)(u²−Δ²)² + K0   Δ+u_s ≤ u < u_c (branch 2: Mooney-Rivlin)
//      = f(u_c)                                        u ≥ u_c         (branch 3: the bond snaps)
// K0 = (2/3)BΔ⁴ per ordered bond makes the reference lattice's energy zero. C⁰ at Δ+u_s (slope jump
// (A/6)(2Δ+u_s)) and at u_c.
struct PairMarder {
  static constexpr std::string_view name = "marder";
  explicit PairMarder(const LawParams& p)
      : a6(p.A / 6),
        b9(p.B / 9),
        d(p.spacing),
        d2(p.spacing * p.spacing),
        knee(p.spacing + p.short_width),
        inv_us(1 / p.short_width),
        k0(2.0 / 3.0 * p.B * d2 * d2) {}
  VD operator()(double u, double uc) const {
    if (u >= uc) return {below(uc).v, 0.0};
    return below(u);
  }
  VD below(double u) const {
    const double s = u * u - d2;  // u² − Δ²
    const double quartic = b9 * s * s + k0, dquartic = 4 * b9 * s * u;
    if (u < knee) return {a6 * s * (u - d) * inv_us + quartic, a6 * (u - d) * (3 * u + d) * inv_us + dquartic};
    return {a6 * s + quartic, 2 * a6 * u + dquartic};
  }
  double a6, b9, d, d2, knee, inv_us, k0;
};

// The C¹ variant (§3, not in the paper): branch 1's A-part becomes (A/6)[(1+4Δ/u_s)s² − (2Δ/u_s²)s³],
// s = u − Δ, which matches branch 2's value and slope at Δ+u_s and keeps f'(Δ) = 0.
struct PairMarderC1 {
  static constexpr std::string_view name = "marder-c1";
  explicit PairMarderC1(const LawParams& p)
      : a6(p.A / 6),
        b9(p.B / 9),
        d(p.spacing),
        d2(p.spacing * p.spacing),
        knee(p.spacing + p.short_width),
        c2(1 + 4 * p.spacing / p.short_width),
        c3(2 * p.spacing / (p.short_width * p.short_width)),
        k0(2.0 / 3.0 * p.B * d2 * d2) {}
  VD operator()(double u, double uc) const {
    if (u >= uc) return {below(uc).v, 0.0};
    return below(u);
  }
  VD below(double u) const {
    const double s2 = u * u - d2;
    const double quartic = b9 * s2 * s2 + k0, dquartic = 4 * b9 * s2 * u;
    if (u < knee) {
      const double s = u - d;
      return {a6 * s * s * (c2 - c3 * s) + quartic, a6 * s * (2 * c2 - 3 * c3 * s) + dquartic};
    }
    return {a6 * s2 + quartic, 2 * a6 * u + dquartic};
  }
  double a6, b9, d, d2, knee, c2, c3, k0;
};

// A softening pair term (not in the paper; a lever for running cracks): the paper's f up to
// u_c − L (L = the cut-off width), then C + (f(u) − C)(1 − S(t)) with the C² smoothstep S of t =
// (u − u_c + L)/L and C = f(u_c − L), constant C beyond u_c. The pair force fades to zero over L instead
// of pulling hardest at u_c and then snapping; with the smoothstep cut-off over the same L, a bond
// loses its pair and three-body terms together. Identical to PairMarder below u_c − L.
struct PairMarderSoft {
  static constexpr std::string_view name = "marder-soft";
  explicit PairMarderSoft(const LawParams& p) : f(p), L(p.cutoff_width), inv_L(1 / p.cutoff_width) {}
  VD operator()(double u, double uc) const {
    const double t = (u - uc + L) * inv_L;
    if (t <= 0) return f.below(u);
    const double c = f.below(uc - L).v;
    if (t >= 1) return {c, 0.0};
    const VD b = f.below(u);
    const double t2 = t * t, w = 1 - t;
    const double S = t2 * t * (10 - 15 * t + 6 * t2), dS = 30 * t2 * w * w * inv_L;
    return {c + (b.v - c) * (1 - S), b.d * (1 - S) - (b.v - c) * dS};
  }
  PairMarder f;
  double L, inv_L;
};

// ------------------------------------------------------------------------------------------ h(u)
// h(u) = 1/(1 + exp((u − u_c)/w)), h' = −h(1−h)/w, computed from e = exp(x) without cancellation.
// Beyond |x| = 40 the exponential is below 5e-18 of 1: h is set to exactly 1 or 0 with h' = 0 (a
// step of 4e-18 relative, below round-off), which spares the exponential for most bonds.
struct CutoffFermi {
  static constexpr std::string_view name = "fermi";
  explicit CutoffFermi(const LawParams& p) : inv_w(1 / p.cutoff_width) {}
  VD operator()(double u, double uc) const {
    const double x = (u - uc) * inv_w;
    if (x < -40) return {1.0, 0.0};
    if (x > 40) return {0.0, 0.0};
    const double e = std::exp(x);
    const double h = 1 / (1 + e);
    return {h, -e * h * h * inv_w};
  }
  double inv_w;
};

// A softening cut-off with compact support (not in the paper; a lever for running cracks): h ≡ 1
// exactly for u ≤ u_c − L, so the far field is Mooney-Rivlin however close it is to u_c, then a C²
// decay to 0 at u_c, h = 1 − S(t), S(t) = 10t³ − 15t⁴ + 6t⁵, t = (u − u_c + L)/L, with L the cut-off
// width. The Fermi function concentrates the whole three-body energy it releases within a few widths
// (a cohesive force spike ~ |g|/(4w)); this spreads it over L: peak force ~ (15/8)|g|/L.
struct CutoffSmoothstep {
  static constexpr std::string_view name = "smoothstep";
  explicit CutoffSmoothstep(const LawParams& p) : L(p.cutoff_width), inv_L(1 / p.cutoff_width) {}
  VD operator()(double u, double uc) const {
    const double t = (u - uc + L) * inv_L;
    if (t <= 0) return {1.0, 0.0};
    if (t >= 1) return {0.0, 0.0};
    const double t2 = t * t, w = 1 - t;
    return {1 - t2 * t * (10 - 15 * t + 6 * t2), -30 * t2 * w * w * inv_L};
  }
  double L, inv_L;
};

// No cut-off: bonds never fail (the continuum-limit checks; elastic runs).
struct CutoffNone {
  static constexpr std::string_view name = "none";
  explicit CutoffNone(const LawParams&) {}
  VD operator()(double, double) const { return {1.0, 0.0}; }
};

// ------------------------------------------------------------------------------------------ g(X)
// g(X) = −(B/27)(X + 2Δ²)² = c2 X² + c1 X + c0. `quadratic` tells the force loop that it may use the
// O(neighbours) moment form of the three-body sum (forces.cpp) instead of the O(neighbours²) pair loop;
// an evaluator that is not a quadratic polynomial sets it false and gets the pair loop.
struct AngleMarder {
  static constexpr std::string_view name = "marder";
  static constexpr bool quadratic = true;
  explicit AngleMarder(const LawParams& p)
      : c2(-p.B / 27),
        c1(-4 * p.B * p.spacing * p.spacing / 27),
        c0(-4 * p.B * p.spacing * p.spacing * p.spacing * p.spacing / 27) {}
  VD operator()(double X) const { return {(c2 * X + c1) * X + c0, 2 * c2 * X + c1}; }
  double c2, c1, c0;
};

// The same g evaluated by the general pair loop over neighbour pairs: a check of the moment form, and
// the template for a g that is not quadratic.
struct AngleMarderPairwise : AngleMarder {
  static constexpr std::string_view name = "marder-pairwise";
  static constexpr bool quadratic = false;
  using AngleMarder::AngleMarder;
};

// ------------------------------------------------------------------------------------------ weight
// The weight of node i's three-body term. The paper's (`pair`): each ordered pair (j, k) carries
// h(u_ij) h(u_ik) and nothing else, so a node that has lost a neighbour keeps the rest of its
// three-body sum, which is not bounded below at a free surface (rubber-lattice-validation.md §D.4).
// `all_bonds` (not in the paper; a lever for running cracks): node i's whole three-body term is
// multiplied by W_i = Π_{s=1..6} h(u_is), the product of the cut-offs of all six slots (a missing or
// removed neighbour counts as h = 0), so a node that loses a neighbour fades to the bounded pair law:
//
//   E_i = Σ_s f(u_is) + W_i Σ_{j≠k} h_j h_k g(a_j·a_k),   ∂W_i/∂a_s = (Π_{t≠s} h_t) h'_s â_s.
//
// With complete shells and bonds far below u_c, W_i = 1 (exactly for a compact cut-off, up to the Fermi
// tail otherwise): the far field is still Mooney-Rivlin. Free edges and crack faces carry the pair law.
// `all_bonds` is a compile-time switch of the force loop (forces.cpp), so the default costs nothing.
struct WeightPair {
  static constexpr std::string_view name = "pair";
  static constexpr bool all_bonds = false;
  explicit WeightPair(const LawParams&) {}
};
struct WeightAllBonds {
  static constexpr std::string_view name = "all_bonds";
  static constexpr bool all_bonds = true;
  explicit WeightAllBonds(const LawParams&) {}
};

// ------------------------------------------------------------------------------------------ registry
using PairLaw = std::variant<PairMarder, PairMarderC1, PairMarderSoft>;
using CutoffLaw = std::variant<CutoffFermi, CutoffSmoothstep, CutoffNone>;
using AngleLaw = std::variant<AngleMarder, AngleMarderPairwise>;
using ThreeBodyWeight = std::variant<WeightPair, WeightAllBonds>;

// The evaluator of that name; UsageError naming `key` and listing the names otherwise.
PairLaw make_pair_law(std::string_view name, const LawParams& p, std::string_view key = "law.pair");
CutoffLaw make_cutoff_law(std::string_view name, const LawParams& p, std::string_view key = "law.cutoff");
AngleLaw make_angle_law(std::string_view name, const LawParams& p, std::string_view key = "law.angle");
ThreeBodyWeight make_three_body_weight(std::string_view name, const LawParams& p,
                                       std::string_view key = "law.three_body_weight");
std::vector<std::string> pair_law_names();
std::vector<std::string> cutoff_law_names();
std::vector<std::string> angle_law_names();
std::vector<std::string> three_body_weight_names();

// The whole law: parameters, the three evaluators and the three-body weight.
struct BondLaw {
  LawParams params;
  PairLaw pair{PairMarder(params)};
  CutoffLaw cutoff{CutoffFermi(params)};
  AngleLaw angle{AngleMarder(params)};
  ThreeBodyWeight weight{WeightPair(params)};
};
BondLaw make_bond_law(const LawParams& p, std::string_view pair = "marder", std::string_view cutoff = "fermi",
                      std::string_view angle = "marder", std::string_view weight = "pair");

}  // namespace frac::rubber
