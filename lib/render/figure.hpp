#pragma once
// What a picture shows, in world coordinates (metres, y up), independent of how it is drawn:
// filled polygons (cells), dots (rubber nodes), coloured segments (beams, bonds), markers (broken
// links), colour bars, a legend and a title. render/canvas draws a Figure with Cairo to PNG or SVG.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "geometry/vec2.hpp"
#include "render/colour.hpp"

namespace frac::render {

using geometry::Vec2;

// Vertices of a cell in world coordinates: the body-frame vertices (relative to the centroid) turned
// by `angle` (rad, counter-clockwise) about the centroid, then moved to `position`.
std::vector<Vec2> world_polygon(std::span<const Vec2> body, const Vec2& position, double angle);

struct FilledPolygon {
  std::vector<Vec2> vertex;
  Rgb fill;
};
struct Dot {
  Vec2 at;
  Rgb fill;
};
struct Segment {
  Vec2 a, b;
  Rgb colour;
};
struct LegendEntry {
  Rgb colour;
  std::string text;
};

struct Figure {
  std::vector<FilledPolygon> polygons;
  std::vector<Dot> dots;
  double dot_radius = 0.0;        // m
  std::vector<Segment> segments;  // drawn over the polygons and dots
  std::vector<Vec2> markers;      // broken links: small crosses, drawn last
  Rgb marker_colour{0.0, 0.0, 0.0};
  double link_length = 0.0;              // m, a typical beam or bond length: sets line widths and marker sizes
  std::vector<ColourScale> colour_bars;  // drawn right of the plot, in this order
  std::vector<LegendEntry> legend;       // swatches under the colour bars
  std::string legend_title;
  std::string title;
  std::array<double, 4> view{0, 0, 1, 1};  // m: xmin, ymin, xmax, ymax shown
  bool axes = false;                       // a frame with ticks and labels in metres
};

// The smallest box holding every polygon, dot (with its radius) and segment; {0,0,1,1} for an empty
// figure. `margin` is added on each side as a fraction of the larger extent.
std::array<double, 4> content_bounds(const Figure& f, double margin = 0.02);
// The union of two boxes.
std::array<double, 4> merge_bounds(const std::array<double, 4>& a, const std::array<double, 4>& b);

}  // namespace frac::render
