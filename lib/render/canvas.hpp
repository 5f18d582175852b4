#pragma once
// Draws a Figure with Cairo and writes it as PNG (cairo image surface) or SVG (cairo SVG surface).
// The picture is made in memory and written under a temporary name in the target's folder, then renamed
// into place, so it is either whole or absent; "-" writes to standard output. The only file that
// includes cairo.h.
#include <array>
#include <string>

#include "render/figure.hpp"

namespace frac::render {

enum class ImageFormat { png, svg };

// By the file name's extension (.png or .svg, any case); UsageError naming `option` otherwise.
ImageFormat format_from_name(const std::string& path, const std::string& option = "--output");
// "png" or "svg"; UsageError naming `option` otherwise.
ImageFormat format_from_text(const std::string& text, const std::string& option = "--format");

struct CanvasSize {
  int width = 1000;  // pixels (SVG: points)
  int height = 0;    // 0: from the aspect ratio of the figure's view
};

// Width and height the picture gets.
std::array<int, 2> canvas_pixels(const Figure& f, const CanvasSize& size);

// Draws `f` and writes it to `path` ("-": standard output, refused when it is a terminal), with
// `provenance` (frac::provenance_line; "" for none) in a PNG text chunk or the SVG's <metadata>.
// UsageError for a missing folder; RuntimeError when the file cannot be written.
void write_figure(const Figure& f, const CanvasSize& size, ImageFormat format, const std::string& path,
                  const std::string& provenance);

}  // namespace frac::render
