#include "render/picture_files.hpp"

#include <cctype>
#include <cstdio>

#include "core/error.hpp"

namespace frac::render {

std::string numbered_name(const std::string& pattern, long long number) {
  std::string out;
  int fields = 0;
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    if (pattern[k] != '%') {
      out += pattern[k];
      continue;
    }
    if (k + 1 < pattern.size() && pattern[k + 1] == '%') {
      out += '%';
      ++k;
      continue;
    }
    std::size_t j = k + 1;
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
    if (j >= pattern.size() || pattern[j] != 'd' || j - k > 4)
      throw UsageError("--output: '" + pattern + "': the only pattern allowed is a frame number such as %04d");
    const int width = j > k + 1 ? std::stoi(pattern.substr(k + 1, j - k - 1)) : 0;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*lld", width, number);
    out += buf;
    ++fields;
    k = j;
  }
  if (fields != 1)
    throw UsageError("--output: '" + pattern +
                     "': a frame sequence needs one frame-number pattern, e.g. picture-%04d.png");
  return out;
}

std::array<int, 2> write_frame_picture(const RunPicture& picture, long long frame, const CanvasSize& size,
                                       ImageFormat format, const std::string& path, const std::string& provenance) {
  const Figure fig = picture.figure(frame);
  write_figure(fig, size, format, path, provenance);
  return canvas_pixels(fig, size);
}

void write_picture_sequence(const RunPicture& picture, const std::vector<long long>& frames, const CanvasSize& size,
                            ImageFormat format, const std::string& pattern, const std::string& provenance,
                            const std::vector<FileRole>& inputs) {
  for (std::size_t s = 0; s < frames.size(); ++s) {
    check_file_roles(inputs, {{"-o", numbered_name(pattern, static_cast<long long>(s))}});
    write_figure(picture.figure(frames[s]), size, format, numbered_name(pattern, static_cast<long long>(s)),
                 provenance);
  }
}

}  // namespace frac::render
