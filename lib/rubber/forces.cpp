#include "rubber/forces.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "rubber/failures.hpp"

namespace frac::rubber {
namespace {

// The six slots of node i as seen from i: bond vector a (from i to the neighbour), h, h'/u, f'/u.
struct Slots {
  double ax[6], ay[6], h[6], hpu[6], fpu[6];
};

inline void load_slots(const ForceContext& c, std::size_t i, Slots& s) {
  const BondData* bd = c.bond;
  for (int k = 0; k < 3; ++k) {
    const BondData& d = bd[3 * i + static_cast<std::size_t>(k)];
    s.ax[k] = d.bx;
    s.ay[k] = d.by;
    s.h[k] = d.h;
    s.hpu[k] = d.hpu;
    s.fpu[k] = d.fpu;
  }
  for (int k = 3; k < 6; ++k) {
    const auto j = static_cast<std::size_t>(c.nbr[6 * i + static_cast<std::size_t>(k)]);
    const BondData& d = bd[3 * j + static_cast<std::size_t>(k - 3)];
    s.ax[k] = -d.bx;
    s.ay[k] = -d.by;
    s.h[k] = d.h;
    s.hpu[k] = d.hpu;
    s.fpu[k] = d.fpu;
  }
}

// The weight W = Π_s h_s of a node's three-body term (WeightAllBonds) and, for each slot, the product of
// the other five, Π_{t≠s} h_t = ∂W/∂h_s (prefix and suffix products: no division, exact when an h is 0).
inline double all_bonds_weight(const Slots& s, double* others) {
  double prefix[6], suffix = 1;
  double p = 1;
  for (int k = 0; k < 6; ++k) {
    prefix[k] = p;
    p *= s.h[k];
  }
  for (int k = 5; k >= 0; --k) {
    others[k] = prefix[k] * suffix;
    suffix *= s.h[k];
  }
  return p;
}

// Three-body energy T_i and the derivatives D(i,s) (pair term included) for a quadratic g, through the
// moments of the neighbour vectors. With Energy, only T is computed. With the weight over all bonds
// (Wt::all_bonds) the three-body part is W T, and its derivative W ∂T/∂a_s + T (Π_{t≠s} h_t) h'_s â_s.
// The residual part of T, −Σ_{s≠t} h_s h_t c_st, and its derivatives 2·(−Σ_{t≠s} c_st h_t) into dh[s].
inline double residual_part(const double* res, const Slots& s, double* dh) {
  double T = 0;
  for (int k = 0; k < 6; ++k) {
    double r = 0;
    for (int t = 0; t < 6; ++t) r += res[6 * k + t] * s.h[t];  // c_kk = 0
    T -= s.h[k] * r;
    dh[k] = -2 * r;
  }
  return T;
}

template <bool Energy, class Wt, class G>
inline double centre_moments(const G& g, const Slots& s, double* D, const double* res) {
  double H1 = 0, H2 = 0, Sx = 0, Sy = 0, Mxx = 0, Mxy = 0, Myy = 0, P2 = 0, P4 = 0;
  for (int k = 0; k < 6; ++k) {
    const double h = s.h[k], ax = s.ax[k], ay = s.ay[k];
    const double hx = h * ax, hy = h * ay;
    const double r2 = ax * ax + ay * ay;
    const double q = h * h * r2;
    H1 += h;
    H2 += h * h;
    Sx += hx;
    Sy += hy;
    Mxx += hx * ax;
    Mxy += hx * ay;
    Myy += hy * ay;
    P2 += q;
    P4 += q * r2;
  }
  const double c2 = g.c2, c1 = g.c1, c0 = g.c0;
  double T = c2 * (Mxx * Mxx + 2 * Mxy * Mxy + Myy * Myy - P4) + c1 * (Sx * Sx + Sy * Sy - P2) + c0 * (H1 * H1 - H2);
  double dres[6] = {0, 0, 0, 0, 0, 0};
  if (res) [[unlikely]]
    T += residual_part(res, s, dres);
  // The weight and the products of the other slots' cut-offs (only with Wt::all_bonds; the paper's
  // path computes exactly what it did without the weight).
  double others[6];
  double W = 1;
  if constexpr (Wt::all_bonds) W = all_bonds_weight(s, others);
  if constexpr (Energy) {
    return W * T;
  } else {
    const double c2_4W = 4 * c2 * W, c1_2W = 2 * c1 * W;
    for (int k = 0; k < 6; ++k) {
      const double h = s.h[k], ax = s.ax[k], ay = s.ay[k];
      const double r2 = ax * ax + ay * ay;
      const double Max = Mxx * ax + Mxy * ay, May = Mxy * ax + Myy * ay;
      const double aMa = ax * Max + ay * May, Sa = Sx * ax + Sy * ay;
      const double hr2 = h * r2;
      // ∂T/∂a at fixed h, then the chain rule through h(|a|) along a (h' â = (h'/u) a), plus f' â;
      // weighted: W ∂T/∂a + T (Π_{t≠s} h_t) h'_s â_s.
      const double coef = 2 * (c2 * (aMa - hr2 * r2) + c1 * (Sa - hr2) + c0 * (H1 - h)) + dres[k];
      double dT = coef;
      if constexpr (Wt::all_bonds) dT = W * coef + T * others[k];
      const double along = dT * s.hpu[k] + s.fpu[k];
      D[2 * k] = h * (c2_4W * (Max - hr2 * ax) + c1_2W * (Sx - h * ax)) + along * ax;
      D[2 * k + 1] = h * (c2_4W * (May - hr2 * ay) + c1_2W * (Sy - h * ay)) + along * ay;
    }
    return 0;
  }
}

// The same by the loop over the 15 unordered pairs of slots (30 ordered pairs): any g.
template <bool Energy, class Wt, class G>
inline double centre_pairs(const G& g, const Slots& s, double* D, const double* res) {
  double S1[6] = {}, S2x[6] = {}, S2y[6] = {};
  double T = 0;
  for (int j = 0; j < 6; ++j)
    for (int k = j + 1; k < 6; ++k) {
      const double X = s.ax[j] * s.ax[k] + s.ay[j] * s.ay[k];
      const VD gv = g(X);
      T += 2 * s.h[j] * s.h[k] * gv.v;
      if constexpr (!Energy) {
        S1[j] += s.h[k] * gv.v;
        S1[k] += s.h[j] * gv.v;
        S2x[j] += s.h[k] * gv.d * s.ax[k];
        S2y[j] += s.h[k] * gv.d * s.ay[k];
        S2x[k] += s.h[j] * gv.d * s.ax[j];
        S2y[k] += s.h[j] * gv.d * s.ay[j];
      }
    }
  if (res) [[unlikely]] {
    double dres[6];
    T += residual_part(res, s, dres);
    for (int k = 0; k < 6; ++k) S1[k] += 0.5 * dres[k];  // S1 is half of ∂T/∂h
  }
  if constexpr (Wt::all_bonds) {
    double others[6];
    const double W = all_bonds_weight(s, others);
    if constexpr (Energy) {
      return W * T;
    } else {
      for (int k = 0; k < 6; ++k) {
        const double along = (2 * W * S1[k] + T * others[k]) * s.hpu[k] + s.fpu[k];
        D[2 * k] = 2 * W * s.h[k] * S2x[k] + along * s.ax[k];
        D[2 * k + 1] = 2 * W * s.h[k] * S2y[k] + along * s.ay[k];
      }
      return 0;
    }
  } else {
    if constexpr (!Energy) {
      for (int k = 0; k < 6; ++k) {
        const double along = 2 * s.hpu[k] * S1[k] + s.fpu[k];
        D[2 * k] = 2 * s.h[k] * S2x[k] + along * s.ax[k];
        D[2 * k + 1] = 2 * s.h[k] * S2y[k] + along * s.ay[k];
      }
    }
    return T;
  }
}

template <bool Energy, class Wt, class G>
inline double centre(const G& g, const Slots& s, double* D, const double* res) {
  if constexpr (G::quadratic)
    return centre_moments<Energy, Wt>(g, s, D, res);
  else
    return centre_pairs<Energy, Wt>(g, s, D, res);
}

// Energy-neutral failure at node i: a slot whose bond failed in this evaluation (kFreezing) leaves the
// node's three-body sum (h = 0: out of the moments, no force), and the terms that contain it are added to
// the node's frozen energy at their value when the bond crossed u_c. The step moved every node along a
// straight line from its previous position; the crossing is where the bond's length along that line is
// u_c, and there the shell is interpolated (h re-evaluated; the failing bond exactly at u_c, as f is
// frozen at f(u_c)). Freezing the terms at the current configuration instead would book the motion past
// the crossing as energy no force did: an error of O(dt) per failure, of one sign. Without a previous
// configuration (the first evaluation) the current one is used. Only node i's own pass writes frozen[i].
template <class Wt, class H, class G>
inline void freeze_failing(ForceContext& c, const H& cut, const G& g, std::size_t i, Slots& s) {
  std::size_t bond[6];
  bool failing = false;
  for (std::size_t k = 0; k < 6; ++k) {
    const auto j = static_cast<std::size_t>(c.nbr[6 * i + k]);
    bond[k] = k < 3 ? 3 * i + k : 3 * j + k - 3;
    failing = failing || c.status[bond[k]] == kFreezing;
  }
  if (!failing) return;
  // The change of each slot's vector over the step (zero for missing neighbours, whose h is 0).
  double dx[6] = {}, dy[6] = {};
  if (c.x_prev) {
    const double mx = c.x[i] - c.x_prev[i], my = c.y[i] - c.y_prev[i];
    for (std::size_t k = 0; k < 6; ++k) {
      const auto j = static_cast<std::size_t>(c.nbr[6 * i + k]);
      if (j >= c.n) continue;
      dx[k] = c.x[j] - c.x_prev[j] - mx;
      dy[k] = c.y[j] - c.y_prev[j] - my;
    }
  }
  // For each failing slot, how far back along the step it crossed u_c: back = 1 − θ, θ in [0, 1] with
  // |a − back d| = u_c, the root nearest the current configuration of
  // |d|² back² − 2 (a·d) back + |a|² − u_c² = 0.
  std::size_t order[6];
  double back_of[6];
  std::size_t count = 0;
  for (std::size_t k = 0; k < 6; ++k) {
    if (c.status[bond[k]] != kFreezing) continue;
    const double uc = c.cutoff[bond[k]];
    const double dd = dx[k] * dx[k] + dy[k] * dy[k], ad = s.ax[k] * dx[k] + s.ay[k] * dy[k];
    const double excess = s.ax[k] * s.ax[k] + s.ay[k] * s.ay[k] - uc * uc;  // > 0: past u_c now
    double back = 0;
    if (dd > 0 && ad > 0) back = std::min(1.0, excess / (ad + std::sqrt(std::max(0.0, ad * ad - dd * excess))));
    back_of[k] = back;
    order[count++] = k;
  }
  // The first to cross first: the terms it shares with a later one are frozen while that one still holds.
  std::stable_sort(order, order + count, [&](std::size_t a, std::size_t b) { return back_of[a] > back_of[b]; });
  bool gone[6];  // out of the sum: failed before (h = 0 in s already) or frozen just now
  for (std::size_t m = 0; m < 6; ++m) gone[m] = c.status[bond[m]] != kIntact && c.status[bond[m]] != kFreezing;
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t k = order[r];
    const double uc = c.cutoff[bond[k]], back = back_of[k];
    Slots t = s;
    for (std::size_t m = 0; m < 6; ++m) {
      if (gone[m]) continue;
      t.ax[m] -= back * dx[m];
      t.ay[m] -= back * dy[m];
      const double um = std::sqrt(t.ax[m] * t.ax[m] + t.ay[m] * t.ay[m]);
      if (m == k) {
        t.ax[m] *= uc / um;
        t.ay[m] *= uc / um;
        t.h[m] = cut(uc, uc).v;
      } else {
        t.h[m] = cut(um, c.cutoff[bond[m]]).v;
      }
    }
    const double with = centre<true, Wt>(g, t, nullptr, c.residual);
    t.h[k] = 0;
    c.frozen[i] += with - centre<true, Wt>(g, t, nullptr, c.residual);
    s.h[k] = s.hpu[k] = s.fpu[k] = 0;
    gone[k] = true;
  }
}

template <class P, class H, class G, DampingKind K, class Wt>
class Passes final : public ForcePasses {
 public:
  Passes(const P& pair, const H& cut, const G& angle) : pair_(pair), cut_(cut), angle_(angle) {}

  void bonds(ForceContext& c, std::size_t i0, std::size_t i1, int worker) const override {
    const P pair = pair_;  // local copies: no store of the loop can alias them
    const H cut = cut_;
    const double* x = c.x;
    const double* y = c.y;
    const std::int32_t* nbr = c.nbr;
    int events = 0, breaks = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      const double xi = x[i], yi = y[i];
      for (std::size_t s = 0; s < 3; ++s) {
        const std::size_t b = 3 * i + s;
        BondData& d = c.bond[b];
        if (c.status[b] != kIntact) {  // (no kFreezing here: settle_failures ended them after their evaluation)
          d = BondData{0, 0, 0, 0, 0, 0};
          continue;
        }
        const auto j = static_cast<std::size_t>(nbr[6 * i + s]);
        double bx = x[j] - xi, by = y[j] - yi;
        if (c.shift) {
          bx += c.shift[2 * b];
          by += c.shift[2 * b + 1];
        }
        const double u = std::sqrt(bx * bx + by * by);
        const double inv_u = 1 / u;
        const double uc = c.cutoff[b];
        if (u > uc && c.track) [[unlikely]] {
          if (bond_fails(c, b, u, uc, events, breaks)) {
            // A kFreezing bond keeps its vector for the centres of its ends, which freeze its terms; it exerts
            // nothing.
            d = c.freeze ? BondData{bx, by, 0, 0, 0, 0} : BondData{0, 0, 0, 0, 0, 0};
            continue;
          }
        }
        const VD f = pair(u, uc);
        const VD hv = cut(u, uc);
        d.bx = bx;
        d.by = by;
        d.h = hv.v;
        d.hpu = hv.d * inv_u;
        d.fpu = f.d * inv_u;
        if constexpr (K == DampingKind::uniform) {
          d.kel = c.beta * inv_u * inv_u;
        } else if constexpr (K == DampingKind::near_failure) {
          const double ramp = (u - c.damping_onset) / (uc - c.damping_onset);
          d.kel = ramp <= 0 ? 0.0 : c.beta * (ramp < 1 ? ramp : 1.0) * inv_u * inv_u;
        }
      }
    }
    c.events[worker] += events;
    c.breaks[worker] += breaks;
  }

  void centres(ForceContext& c, std::size_t i0, std::size_t i1) const override {
    const G g = angle_;
    const H cut = cut_;
    const bool freeze = c.freeze;
    Slots s;
    for (std::size_t i = i0; i < i1; ++i) {
      load_slots(c, i, s);
      if (freeze) [[unlikely]]
        freeze_failing<Wt>(c, cut, g, i, s);
      centre<false, Wt>(g, s, c.D + 12 * i, c.residual);
    }
  }

  void gather(ForceContext& c, std::size_t i0, std::size_t i1, int worker) const override {
    const double* D = c.D;
    const std::int32_t* nbr = c.nbr;
    int bad = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      double fx = 0, fy = 0;
      const double* Di = D + 12 * i;
      for (std::size_t s = 0; s < 6; ++s) {
        fx += Di[2 * s];
        fy += Di[2 * s + 1];
      }
      for (std::size_t s = 0; s < 6; ++s) {
        const auto j = static_cast<std::size_t>(nbr[6 * i + s]);
        const std::size_t r = s < 3 ? s + 3 : s - 3;
        fx -= D[12 * j + 2 * r];
        fy -= D[12 * j + 2 * r + 1];
      }
      if constexpr (K != DampingKind::none) {
        const double vxi = c.vx[i], vyi = c.vy[i];
        for (std::size_t s = 0; s < 6; ++s) {
          const auto j = static_cast<std::size_t>(nbr[6 * i + s]);
          const BondData& d = s < 3 ? c.bond[3 * i + s] : c.bond[3 * j + s - 3];
          const std::size_t jv = j < c.n ? j : i;  // the sentinel has no velocity (its kel is 0)
          const double p = d.kel * ((c.vx[jv] - vxi) * d.bx + (c.vy[jv] - vyi) * d.by);
          fx += p * d.bx;
          fy += p * d.by;
        }
      }
      if (!(std::isfinite(fx) && std::isfinite(fy))) [[unlikely]]
        ++bad;
      c.ax[i] = fx * c.inv_mass;
      c.ay[i] = fy * c.inv_mass;
    }
    c.nonfinite[worker] += bad;
  }

  void energy(ForceContext& c, std::size_t k0, std::size_t k1) const override {
    const P pair = pair_;  // local copies: no store of the loop can alias them
    const G g = angle_;
    const std::size_t block = ForceContext::kEnergyBlock;
    Slots s;
    for (std::size_t k = k0; k < k1; ++k) {
      double ep = 0, et = 0;
      const std::size_t end = std::min(c.n, (k + 1) * block);
      for (std::size_t i = k * block; i < end; ++i) {
        for (std::size_t f = 0; f < 3; ++f) {
          const std::size_t b = 3 * i + f;
          const double uc = c.cutoff[b];
          if (c.status[b] == kBroken) {
            ep += 2 * pair(uc, uc).v;
          } else if (c.status[b] == kIntact) {
            const auto j = static_cast<std::size_t>(c.nbr[6 * i + f]);
            double bx = c.x[j] - c.x[i], by = c.y[j] - c.y[i];
            if (c.shift) {
              bx += c.shift[2 * b];
              by += c.shift[2 * b + 1];
            }
            ep += 2 * pair(std::sqrt(bx * bx + by * by), uc).v;
          }
        }
        load_slots(c, i, s);
        et += centre<true, Wt>(g, s, nullptr, c.residual);
        if (c.residual) [[unlikely]]  // the constant Σ c_st over the node's existing slots
          for (std::size_t a = 0; a < 6; ++a)
            for (std::size_t b = 0; b < 6; ++b)
              if (a != b && static_cast<std::size_t>(c.nbr[6 * i + a]) < c.n &&
                  static_cast<std::size_t>(c.nbr[6 * i + b]) < c.n)
                et += c.residual[6 * a + b];
      }
      c.block_energy[2 * k] = ep;
      c.block_energy[2 * k + 1] = et;
    }
  }

 private:
  P pair_;
  H cut_;
  G angle_;
};

}  // namespace

void virial_blocks(ForceContext& c, std::size_t k0, std::size_t k1) {
  const std::size_t block = ForceContext::kEnergyBlock;
  Slots s;
  for (std::size_t k = k0; k < k1; ++k) {
    double w[4] = {0, 0, 0, 0};
    const std::size_t end = std::min(c.n, (k + 1) * block);
    for (std::size_t i = k * block; i < end; ++i) {
      load_slots(c, i, s);
      const double* D = c.D + 12 * i;
      for (int t = 0; t < 6; ++t) {
        w[0] += D[2 * t] * s.ax[t];
        w[1] += D[2 * t] * s.ay[t];
        w[2] += D[2 * t + 1] * s.ax[t];
        w[3] += D[2 * t + 1] * s.ay[t];
      }
    }
    for (int t = 0; t < 4; ++t) c.block_energy[4 * k + static_cast<std::size_t>(t)] = w[t];
  }
}

std::unique_ptr<const ForcePasses> select_passes(const BondLaw& law, DampingKind damping) {
  return std::visit(
      [damping](const auto& p, const auto& h, const auto& g, const auto& w) -> std::unique_ptr<const ForcePasses> {
        using P = std::decay_t<decltype(p)>;
        using H = std::decay_t<decltype(h)>;
        using G = std::decay_t<decltype(g)>;
        using W = std::decay_t<decltype(w)>;
        switch (damping) {
          case DampingKind::uniform:
            return std::make_unique<Passes<P, H, G, DampingKind::uniform, W>>(p, h, g);
          case DampingKind::near_failure:
            return std::make_unique<Passes<P, H, G, DampingKind::near_failure, W>>(p, h, g);
          default:
            return std::make_unique<Passes<P, H, G, DampingKind::none, W>>(p, h, g);
        }
      },
      law.pair, law.cutoff, law.angle, law.weight);
}

}  // namespace frac::rubber
