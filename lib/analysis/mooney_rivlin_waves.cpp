#include "analysis/mooney_rivlin_waves.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "continuum/mooney_rivlin.hpp"
#include "core/error.hpp"

namespace frac::analysis {
namespace {

// A wave needs a positive speed: zero (b = 2 for shear) counts as none.
double positive_or_nan(double c) { return c > 0 ? c : std::numeric_limits<double>::quiet_NaN(); }

mr::Mat2 stretch_tensor(Stretch s) { return mr::Mat2{{s.x, 0}, {0, s.y}}; }

std::string number(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

}  // namespace

void validate(const MooneyRivlin& m, Stretch s) {
  if (!(m.a > 0) || !std::isfinite(m.a))
    throw UsageError("--a: a must be a positive velocity squared, got " + number(m.a));
  if (!std::isfinite(m.b)) throw UsageError("--b: b must be finite");
  if (!(m.density > 0) || !std::isfinite(m.density))
    throw UsageError("--density: the density must be positive, got " + number(m.density));
  if (!(s.x > 0) || !(s.y > 0) || !std::isfinite(s.x) || !std::isfinite(s.y))
    throw UsageError("--stretch: expected two positive extension ratios, got " + number(s.x) + "x" + number(s.y));
}

MrWaveSpeeds mooney_rivlin_speeds(const MooneyRivlin& m, Stretch s, double direction) {
  validate(m, s);
  const mr::Vec2 n(std::cos(direction), std::sin(direction));
  const mr::Mat2 F = stretch_tensor(s);
  const mr::Speeds c = mr::speeds(F, n, m.a, m.b);
  MrWaveSpeeds out;
  out.direction = direction;
  out.stretch_along = (F.transpose() * n).norm();
  out.shear = positive_or_nan(c.transverse);
  out.longitudinal = positive_or_nan(c.longitudinal);
  out.shear_reference = out.shear / out.stretch_along;
  out.longitudinal_reference = out.longitudinal / out.stretch_along;
  return out;
}

double mach_angle(const MooneyRivlin& m, Stretch s, double speed, bool longitudinal) {
  // speed · sin(alpha) − c(n(alpha)) is −c_y at alpha = 0 and speed − c_x at 90°: bisect.
  auto excess = [&](double alpha) {
    const MrWaveSpeeds c = mooney_rivlin_speeds(m, s, std::numbers::pi / 2 - alpha);
    return speed * std::sin(alpha) - (longitudinal ? c.longitudinal : c.shear);
  };
  double lo = 0, hi = std::numbers::pi / 2;
  if (!(excess(hi) > 0)) return std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

MrStress mooney_rivlin_stress(const MooneyRivlin& m, Stretch s) {
  validate(m, s);
  const mr::Material material{m.a, m.b, m.density};
  const mr::Mat2 F = stretch_tensor(s);
  const mr::Mat2 P = mr::piola(F, material), sigma = mr::cauchy(F, material);
  MrStress out;
  out.piola_xx = P(0, 0);
  out.piola_yy = P(1, 1);
  out.cauchy_xx = sigma(0, 0);
  out.cauchy_yy = sigma(1, 1);
  return out;
}

std::string_view name(LatticeRegime r) {
  switch (r) {
    case LatticeRegime::mooney_rivlin:
      return "mooney-rivlin";
    case LatticeRegime::short_bonds:
      return "short-bonds";
    case LatticeRegime::near_cutoff:
      return "near-cutoff";
    case LatticeRegime::broken:
      return "broken";
    case LatticeRegime::unchecked:
      return "unchecked";
  }
  return "unchecked";
}

LatticeCheck check_lattice(const LatticeParameters& p, Stretch s) {
  if (p.rows_along != "x" && p.rows_along != "y")
    throw UsageError("--rows-along: expected x or y, got '" + p.rows_along + "'");
  if (!(s.x > 0) || !(s.y > 0)) throw UsageError("--stretch: the extension ratios must be positive");
  LatticeCheck out;
  if (!(p.spacing > 0)) {
    out.message = "lattice spacing unknown: the bond lengths were not checked";
    return out;
  }
  // Reference bond directions: 0, 60, 120 degrees with rows along x; 90, 30, 150 with rows along y.
  const double deg = std::numbers::pi / 180;
  const std::array<double, 3> angles = p.rows_along == "x" ? std::array<double, 3>{0.0, 60 * deg, 120 * deg}
                                                           : std::array<double, 3>{90 * deg, 30 * deg, 150 * deg};
  for (std::size_t k = 0; k < 3; ++k) {
    const double dx = std::cos(angles[k]) * s.x, dy = std::sin(angles[k]) * s.y;
    out.families[k] = {angles[k], p.spacing * std::hypot(dx, dy)};
  }
  const auto family = [&](std::size_t k) {
    return "the bonds at " + number(out.families[k].reference_angle / deg) + " deg (reference) are " +
           number(out.families[k].length / p.spacing) + " Delta long";
  };
  std::size_t shortest = 0, longest = 0;
  for (std::size_t k = 1; k < 3; ++k) {
    if (out.families[k].length < out.families[shortest].length) shortest = k;
    if (out.families[k].length > out.families[longest].length) longest = k;
  }
  const double u_min = out.families[shortest].length, u_max = out.families[longest].length;
  const std::string at = "at stretch " + number(s.x) + "x" + number(s.y) + " with rows along " + p.rows_along + ", ";

  if (p.cutoff > 0 && u_max >= p.cutoff) {
    out.regime = LatticeRegime::broken;
    out.message = at + family(longest) + ", at or beyond the cut-off u_c = " + number(p.cutoff / p.spacing) +
                  " Delta: the lattice is not Mooney-Rivlin (bonds fail)";
    return out;
  }
  if (p.short_width >= 0 && u_min < p.spacing + p.short_width) {
    out.regime = LatticeRegime::short_bonds;
    out.message = at + family(shortest) + ", shorter than Delta + u_s = " + number(1 + p.short_width / p.spacing) +
                  " Delta (branch 1 of the pair term): the lattice is not Mooney-Rivlin at this stretch "
                  "(physics/rubber-lattice.md §4); turn the lattice (rows along the other axis) or stretch more";
    return out;
  }
  if (p.cutoff > 0 && p.cutoff_width >= 0 && p.cutoff - u_max < kCutoffClearance * p.cutoff_width) {
    out.regime = LatticeRegime::near_cutoff;
    out.message = at + family(longest) + ", only " + number((p.cutoff - u_max) / std::max(p.cutoff_width, 1e-300)) +
                  " cut-off widths below u_c = " + number(p.cutoff / p.spacing) + " Delta (at least " +
                  number(kCutoffClearance) +
                  " needed): the cut-off stiffens the far field, the lattice is not Mooney-Rivlin "
                  "(rubber-lattice-validation.md §D)";
    return out;
  }
  if (p.short_width < 0) {
    out.message = at +
                  "the short-bond width u_s is unknown: the branch-1 condition (every bond longer than "
                  "Delta + u_s) was not checked; shortest bonds " +
                  number(u_min / p.spacing) + " Delta";
    return out;
  }
  out.regime = LatticeRegime::mooney_rivlin;
  out.message =
      at + "every bond is in branch 2 (" + number(u_min / p.spacing) + " to " + number(u_max / p.spacing) +
      " Delta, above Delta + u_s = " + number(1 + p.short_width / p.spacing) + " Delta" +
      (p.cutoff > 0 && p.cutoff_width >= 0 ? ", at least " + number(kCutoffClearance) + " cut-off widths below u_c"
                                           : std::string(p.cutoff > 0 ? ", below u_c" : ", cut-off not checked")) +
      ")";
  return out;
}

}  // namespace frac::analysis
