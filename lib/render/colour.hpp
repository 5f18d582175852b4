#pragma once
// Colour maps for the pictures of lib/render: a sequential map (viridis) for magnitudes such as speed,
// a diverging map (cool-warm) for signed quantities such as beam strain relative to its breaking
// threshold, and a categorical palette for labels such as fragment ids. Colours are RGB in [0, 1].
#include <cstdint>
#include <string>

namespace frac::render {

struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

enum class Palette { viridis, coolwarm };

// Matplotlib's viridis (perceptually uniform, readable in grey and by colour-blind readers), linearly
// interpolated between 11 samples; t is clamped to [0, 1] (NaN gives the t = 0 end).
Rgb viridis(double t);
// Moreland's cool-warm diverging map: blue at 0, light grey at 0.5, red at 1; t clamped to [0, 1].
Rgb coolwarm(double t);
Rgb sample(Palette p, double t);

// Distinct colours for labels 0, 1, 2, ...: a 9-colour qualitative palette first (no grey in it), then
// hues spaced by the golden angle. Negative labels (no label) and `single` labels (one-cell fragments,
// debris) are light grey.
Rgb category(std::int64_t label);
inline constexpr Rgb kDebrisGrey{0.82, 0.82, 0.82};

// A value range drawn with a palette, and its colour bar's label ("speed (m/s)").
struct ColourScale {
  Palette palette = Palette::viridis;
  double min = 0.0, max = 1.0;
  std::string label;
  // (v - min) / (max - min), clamped to [0, 1]; 0.5 when the range is empty.
  double normalise(double v) const;
  Rgb operator()(double v) const { return sample(palette, normalise(v)); }
};

// "#rrggbb", for messages and tests.
std::string hex(const Rgb& c);

}  // namespace frac::render
