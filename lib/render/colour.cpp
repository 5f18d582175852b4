#include "render/colour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace frac::render {
namespace {

template <std::size_t N>
Rgb interpolate(const std::array<Rgb, N>& table, double t) {
  if (!(t > 0.0)) return table.front();  // also NaN
  if (t >= 1.0) return table.back();
  const double x = t * static_cast<double>(N - 1);
  const auto k = std::min(static_cast<std::size_t>(x), N - 2);
  const double f = x - static_cast<double>(k);
  const Rgb& a = table[k];
  const Rgb& b = table[k + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

// viridis at t = 0, 0.1, ..., 1.
constexpr std::array<Rgb, 11> kViridis{{{0.267004, 0.004874, 0.329415},
                                        {0.282623, 0.140926, 0.457517},
                                        {0.253935, 0.265254, 0.529983},
                                        {0.206756, 0.371758, 0.553117},
                                        {0.163625, 0.471133, 0.558148},
                                        {0.127568, 0.566949, 0.550556},
                                        {0.134692, 0.658636, 0.517649},
                                        {0.266941, 0.748751, 0.440573},
                                        {0.477504, 0.821444, 0.318195},
                                        {0.741388, 0.873449, 0.149561},
                                        {0.993248, 0.906157, 0.143936}}};

// cool-warm at t = 0, 0.125, ..., 1.
constexpr std::array<Rgb, 9> kCoolWarm{{{0.230, 0.299, 0.754},
                                        {0.370, 0.491, 0.904},
                                        {0.552, 0.690, 0.996},
                                        {0.722, 0.817, 0.976},
                                        {0.865, 0.865, 0.865},
                                        {0.958, 0.777, 0.673},
                                        {0.958, 0.604, 0.482},
                                        {0.867, 0.377, 0.301},
                                        {0.706, 0.016, 0.150}}};

// Tableau's qualitative colours without its grey.
constexpr std::array<Rgb, 9> kCategories{{{0.122, 0.467, 0.706},
                                          {1.000, 0.498, 0.055},
                                          {0.173, 0.627, 0.173},
                                          {0.839, 0.153, 0.157},
                                          {0.580, 0.404, 0.741},
                                          {0.549, 0.337, 0.294},
                                          {0.890, 0.467, 0.761},
                                          {0.737, 0.741, 0.133},
                                          {0.090, 0.745, 0.812}}};

Rgb from_hsv(double h, double s, double v) {
  const double c = v * s;
  const double hp = h * 6.0;
  const double x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
  Rgb out;
  if (hp < 1)
    out = {c, x, 0};
  else if (hp < 2)
    out = {x, c, 0};
  else if (hp < 3)
    out = {0, c, x};
  else if (hp < 4)
    out = {0, x, c};
  else if (hp < 5)
    out = {x, 0, c};
  else
    out = {c, 0, x};
  const double m = v - c;
  return {out.r + m, out.g + m, out.b + m};
}

}  // namespace

Rgb viridis(double t) { return interpolate(kViridis, t); }
Rgb coolwarm(double t) { return interpolate(kCoolWarm, t); }

Rgb sample(Palette p, double t) { return p == Palette::viridis ? viridis(t) : coolwarm(t); }

Rgb category(std::int64_t label) {
  if (label < 0) return kDebrisGrey;
  if (label < static_cast<std::int64_t>(kCategories.size())) return kCategories[static_cast<std::size_t>(label)];
  // Golden-angle hues; saturation and value alternate so neighbours in hue still differ.
  const double golden = 0.6180339887498949;
  const double h = std::fmod(0.11 + golden * static_cast<double>(label), 1.0);
  const double s = label % 2 ? 0.55 : 0.75;
  const double v = label % 3 == 0 ? 0.70 : 0.88;
  return from_hsv(h, s, v);
}

double ColourScale::normalise(double v) const {
  const double span = max - min;
  if (!(span > 0.0) || !std::isfinite(span)) return 0.5;
  return std::clamp((v - min) / span, 0.0, 1.0);
}

std::string hex(const Rgb& c) {
  auto byte = [](double x) { return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

}  // namespace frac::render
