#include "render/canvas.hpp"

#include <cairo-svg.h>
#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/provenance_text.hpp"

namespace frac::render {
namespace {

constexpr double kTitleHeight = 34, kPad = 12, kAxesLeft = 80, kAxesBottom = 52, kBarColumn = 104, kLegendColumn = 170,
                 kMinHeight = 280;
constexpr const char* kFont = "DejaVu Sans";

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Pixel layout of a figure: plot area and the world-to-pixel map.
struct Layout {
  int width = 0, height = 0;
  double plot_x = 0, plot_y = 0, plot_w = 0, plot_h = 0;  // plot area
  double scale = 1;                                       // pixels per metre
  double ox = 0, oy = 0;                                  // pixel of (view xmin, view ymax)
  const std::array<double, 4>* view = nullptr;
  double px(double x) const { return ox + scale * (x - (*view)[0]); }
  double py(double y) const { return oy + scale * ((*view)[3] - y); }
};

double right_margin(const Figure& f) {
  return kPad + kBarColumn * static_cast<double>(f.colour_bars.size()) + (f.legend.empty() ? 0.0 : kLegendColumn);
}

Layout make_layout(const Figure& f, const CanvasSize& size) {
  Layout l;
  l.view = &f.view;
  const double vw = std::max(f.view[2] - f.view[0], 1e-300), vh = std::max(f.view[3] - f.view[1], 1e-300);
  const double top = f.title.empty() ? kPad : kTitleHeight;
  const double left = f.axes ? kAxesLeft : kPad, bottom = f.axes ? kAxesBottom : kPad;
  const double right = right_margin(f);
  l.width = std::max(size.width, static_cast<int>(left + right) + 100);
  l.plot_x = left;
  l.plot_y = top;
  l.plot_w = l.width - left - right;
  if (size.height > 0) {
    l.height = std::max(size.height, static_cast<int>(top + bottom) + 50);
  } else {
    const double plot_h = l.plot_w * vh / vw;
    l.height = static_cast<int>(std::clamp(std::ceil(plot_h + top + bottom), kMinHeight, 8.0 * l.width));
    l.height += l.height % 2;  // even: video encoders (yuv420p) need even sizes for a movie of the frames
  }
  l.plot_h = l.height - top - bottom;
  l.scale = std::min(l.plot_w / vw, l.plot_h / vh);
  l.ox = l.plot_x + 0.5 * (l.plot_w - l.scale * vw);
  l.oy = l.plot_y + 0.5 * (l.plot_h - l.scale * vh);
  return l;
}

void set(cairo_t* cr, const Rgb& c, double alpha = 1.0) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

void text_at(cairo_t* cr, double x, double y, const std::string& s, double size, double align_x = 0.0,
             double align_y = 0.0) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align_x * e.x_advance, y + align_y * size * 0.72);
  cairo_show_text(cr, s.c_str());
}

std::string format_tick(double v, double step) {
  if (std::abs(v) < 1e-9 * std::abs(step)) v = 0.0;
  char buf[32];
  const double a = std::abs(v);
  if (v != 0.0 && (a >= 1e4 || a < 1e-3))
    std::snprintf(buf, sizeof buf, "%.3g", v);
  else
    std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Tick positions at 1, 2 or 5 times a power of ten, about `target` of them in [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int target, double* step_out = nullptr) {
  std::vector<double> ticks;
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) {
    if (std::isfinite(lo)) ticks.push_back(lo);
    if (step_out) *step_out = 1.0;
    return ticks;
  }
  const double raw = span / std::max(target, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = p;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) {
      step = m * p;
      break;
    }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  if (step_out) *step_out = step;
  return ticks;
}

void draw_colour_bar(cairo_t* cr, const ColourScale& bar, double x, double top, double h) {
  constexpr double w = 16;
  cairo_pattern_t* grad = cairo_pattern_create_linear(0, top + h, 0, top);
  for (int k = 0; k <= 32; ++k) {
    const double t = k / 32.0;
    const Rgb c = sample(bar.palette, t);
    cairo_pattern_add_color_stop_rgb(grad, t, c.r, c.g, c.b);
  }
  cairo_rectangle(cr, x, top, w, h);
  cairo_set_source(cr, grad);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(grad);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  double step = 1;
  const auto ticks = nice_ticks(bar.min, bar.max, 5, &step);
  for (double t : ticks) {
    const double y = top + h - bar.normalise(t) * h;
    cairo_move_to(cr, x + w, y);
    cairo_line_to(cr, x + w + 4, y);
    cairo_stroke(cr);
    text_at(cr, x + w + 6, y, format_tick(t, step), 11, 0.0, 0.5);
  }
  // The label along the bar, read from bottom to top.
  cairo_save(cr);
  cairo_translate(cr, x + w + 62, top + h / 2);
  cairo_rotate(cr, -std::numbers::pi / 2);
  text_at(cr, 0, 0, bar.label, 12, 0.5, 0.5);
  cairo_restore(cr);
}

void draw_axes(cairo_t* cr, const Layout& l, const std::array<double, 4>& v) {
  const double x0 = l.px(v[0]), x1 = l.px(v[2]), y0 = l.py(v[1]), y1 = l.py(v[3]);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_rectangle(cr, x0, y1, x1 - x0, y0 - y1);
  cairo_stroke(cr);
  double step = 1;
  for (double t : nice_ticks(v[0], v[2], std::max(2, static_cast<int>((x1 - x0) / 90)), &step)) {
    const double x = l.px(t);
    cairo_move_to(cr, x, y0);
    cairo_line_to(cr, x, y0 + 5);
    cairo_stroke(cr);
    text_at(cr, x, y0 + 18, format_tick(t, step), 11, 0.5, 0.0);
  }
  for (double t : nice_ticks(v[1], v[3], std::max(2, static_cast<int>((y0 - y1) / 70)), &step)) {
    const double y = l.py(t);
    cairo_move_to(cr, x0, y);
    cairo_line_to(cr, x0 - 5, y);
    cairo_stroke(cr);
    text_at(cr, x0 - 8, y, format_tick(t, step), 11, 1.0, 0.5);
  }
  text_at(cr, 0.5 * (x0 + x1), y0 + 40, "x (m)", 12, 0.5, 0.0);
  cairo_save(cr);
  cairo_translate(cr, x0 - 62, 0.5 * (y0 + y1));
  cairo_rotate(cr, -std::numbers::pi / 2);
  text_at(cr, 0, 0, "y (m)", 12, 0.5, 0.5);
  cairo_restore(cr);
}

// Plot area: everything in the view, clipped to it; polygons, dots, link segments, then broken-link crosses.
void draw_plot_area(cairo_t* cr, const Figure& f, const Layout& l) {
  const double link_px = f.link_length * l.scale;
  cairo_save(cr);
  cairo_rectangle(cr, l.plot_x, l.plot_y, l.plot_w, l.plot_h);
  cairo_clip(cr);
  const bool outline = link_px > 8.0;
  for (const auto& p : f.polygons) {
    if (p.vertex.size() < 3) continue;
    cairo_move_to(cr, l.px(p.vertex[0].x()), l.py(p.vertex[0].y()));
    for (std::size_t k = 1; k < p.vertex.size(); ++k) cairo_line_to(cr, l.px(p.vertex[k].x()), l.py(p.vertex[k].y()));
    cairo_close_path(cr);
    set(cr, p.fill);
    cairo_fill_preserve(cr);
    // Outlines: thin dark edges when cells are large enough to show them, else the fill colour
    // (closes the hairline seams antialiasing leaves between neighbours).
    if (outline) {
      cairo_set_source_rgba(cr, 0.15, 0.15, 0.15, 0.55);
      cairo_set_line_width(cr, 0.5);
    } else {
      cairo_set_line_width(cr, 0.4);
    }
    cairo_stroke(cr);
  }
  const double dot_px = std::max(0.7, f.dot_radius * l.scale);
  for (const auto& d : f.dots) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, l.px(d.at.x()), l.py(d.at.y()), dot_px, 0, 2 * std::numbers::pi);
    set(cr, d.fill);
    cairo_fill(cr);
  }
  const double line_px = std::clamp(0.06 * link_px, 0.3, 2.0);
  cairo_set_line_width(cr, line_px);
  for (const auto& s : f.segments) {
    cairo_move_to(cr, l.px(s.a.x()), l.py(s.a.y()));
    cairo_line_to(cr, l.px(s.b.x()), l.py(s.b.y()));
    set(cr, s.colour);
    cairo_stroke(cr);
  }
  const double half = std::clamp(0.12 * link_px, 1.5, 4.0);
  cairo_set_line_width(cr, std::max(0.8, line_px));
  set(cr, f.marker_colour);
  for (const auto& m : f.markers) {
    const double x = l.px(m.x()), y = l.py(m.y());
    cairo_move_to(cr, x - half, y - half);
    cairo_line_to(cr, x + half, y + half);
    cairo_move_to(cr, x - half, y + half);
    cairo_line_to(cr, x + half, y - half);
  }
  if (!f.markers.empty()) cairo_stroke(cr);
  cairo_restore(cr);
}

// The legend's title and its entries (colour box and text) from (x, plot top), as far as the plot reaches.
void draw_legend(cairo_t* cr, const Figure& f, const Layout& l, double x) {
  double y = l.plot_y + 14;
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (!f.legend_title.empty()) {
    text_at(cr, x, y, f.legend_title, 12);
    y += 18;
  }
  for (const auto& e : f.legend) {
    if (y > l.plot_y + l.plot_h) break;
    cairo_rectangle(cr, x, y - 10, 12, 12);
    set(cr, e.colour);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
    text_at(cr, x + 18, y, e.text, 11);
    y += 16;
  }
}

void draw(cairo_t* cr, const Figure& f, const Layout& l) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);

  draw_plot_area(cr, f, l);

  cairo_set_source_rgb(cr, 0, 0, 0);
  if (f.axes) draw_axes(cr, l, f.view);
  if (!f.title.empty()) text_at(cr, kPad, kTitleHeight / 2, f.title, 14, 0.0, 0.5);

  // Colour bars, then the legend, in columns right of the plot.
  double x = l.width - right_margin(f) + kPad;
  const double bar_h = std::clamp(0.8 * l.plot_h, 60.0, 360.0);
  const double bar_top = l.plot_y + 0.5 * (l.plot_h - bar_h);
  for (const auto& bar : f.colour_bars) {
    draw_colour_bar(cr, bar, x, bar_top, bar_h);
    x += kBarColumn;
  }
  if (!f.legend.empty()) draw_legend(cr, f, l, x);
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using Context = std::unique_ptr<cairo_t, ContextDeleter>;

cairo_status_t append(void* bytes, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(bytes)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void check(cairo_status_t status, const std::string& path, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw RuntimeError(path + ": cannot " + what + " (" + cairo_status_to_string(status) + ")");
}

}  // namespace

ImageFormat format_from_name(const std::string& path, const std::string& option) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".svg") return ImageFormat::svg;
  throw UsageError(option + ": '" + path + "': the picture's format comes from its extension, .png or .svg");
}

ImageFormat format_from_text(const std::string& text, const std::string& option) {
  const std::string t = lower(text);
  if (t == "png") return ImageFormat::png;
  if (t == "svg") return ImageFormat::svg;
  throw UsageError(option + ": unknown picture format '" + text + "' (png or svg)");
}

std::array<int, 2> canvas_pixels(const Figure& f, const CanvasSize& size) {
  const Layout l = make_layout(f, size);
  return {l.width, l.height};
}

void write_figure(const Figure& f, const CanvasSize& size, ImageFormat format, const std::string& path,
                  const std::string& provenance) {
  const Layout l = make_layout(f, size);
  if (path == "-" && isatty(STDOUT_FILENO))
    throw UsageError("refusing to write a picture to a terminal: give -o FILE or redirect standard output");
  // Made in memory: the provenance goes in before the file is written.
  std::string bytes;
  if (format == ImageFormat::png) {
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, l.width, l.height));
    check(cairo_surface_status(surface.get()), path, "create the picture (too large?)");
    {
      Context cr(cairo_create(surface.get()));
      draw(cr.get(), f, l);
      check(cairo_status(cr.get()), path, "draw the picture");
    }
    cairo_surface_flush(surface.get());
    check(cairo_surface_write_to_png_stream(surface.get(), append, &bytes), path, "write the PNG file");
    if (!provenance.empty()) bytes = io::png_with_text(bytes, io::kProvenanceKey, provenance);
  } else {
    Surface surface(cairo_svg_surface_create_for_stream(append, &bytes, l.width, l.height));
    check(cairo_surface_status(surface.get()), path, "create the SVG file");
    {
      Context cr(cairo_create(surface.get()));
      draw(cr.get(), f, l);
      check(cairo_status(cr.get()), path, "draw the picture");
    }
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()), path, "write the SVG file");
    if (!provenance.empty()) bytes = io::svg_with_metadata(bytes, provenance);
  }
  io::write_file_atomically(path, bytes);
}

}  // namespace frac::render
