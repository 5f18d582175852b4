#include "analysis/wave_speed_theory.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace frac::analysis {

PlaneStressSpeeds plane_stress_speeds(double young, double poisson, double density) {
  if (!(young > 0) || !std::isfinite(young)) throw UsageError("--young: the Young modulus must be positive");
  if (!(density > 0) || !std::isfinite(density)) throw UsageError("--density: the density must be positive");
  if (!(poisson > -1 && poisson < 1)) throw UsageError("--poisson: a plane-stress Poisson ratio lies in (-1, 1)");
  PlaneStressSpeeds out;
  out.longitudinal = std::sqrt(young / (density * (1 - poisson * poisson)));
  out.shear = std::sqrt(young / (2 * density * (1 + poisson)));
  out.bar = std::sqrt(young / density);
  return out;
}

double parse_direction(const std::string& text, const std::string& option) {
  if (text == "radial") return std::numeric_limits<double>::quiet_NaN();
  if (text == "x" || text == "+x") return 0.0;
  if (text == "y" || text == "+y") return std::numbers::pi / 2;
  if (text == "-x") return std::numbers::pi;
  if (text == "-y") return -std::numbers::pi / 2;
  std::string number = text;
  if (number.size() > 3 && number.compare(number.size() - 3, 3, "deg") == 0) number.resize(number.size() - 3);
  std::istringstream in(number);
  double degrees = 0;
  in >> degrees;
  if (!in || in.peek() != std::char_traits<char>::eof() || !std::isfinite(degrees))
    throw UsageError(option + ": expected x, y, -x, -y or an angle in degrees, got '" + text + "'");
  double rad = std::remainder(degrees * std::numbers::pi / 180, 2 * std::numbers::pi);
  if (rad <= -std::numbers::pi) rad += 2 * std::numbers::pi;
  return rad;
}

std::string direction_label(double radians) {
  if (std::isnan(radians)) return "radial";
  const double deg = std::remainder(radians * 180 / std::numbers::pi, 360.0);
  const auto near = [&](double target) { return std::abs(std::remainder(deg - target, 360.0)) < 1e-9; };
  if (near(0)) return "x";
  if (near(90)) return "y";
  if (near(180)) return "-x";
  if (near(-90)) return "-y";
  std::ostringstream out;
  out.precision(6);
  out << deg << "deg";
  return out.str();
}

}  // namespace frac::analysis
