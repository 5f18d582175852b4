#include "io/provenance_text.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdint>

#include "core/error.hpp"

namespace frac::io {
namespace {

constexpr std::string_view kPngSignature = "\x89PNG\r\n\x1a\n";

void put_u32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xffu);
}

std::uint32_t get_u32(std::string_view in, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(in[at + k]);
  return v;
}

// A PNG chunk: length, type, data, CRC-32 of type and data.
std::string png_chunk(std::string_view type, std::string_view data) {
  std::string body(type);
  body += data;
  std::string out;
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  out += body;
  put_u32(out, static_cast<std::uint32_t>(
                   crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  return out;
}

}  // namespace

std::string png_with_text(std::string_view png, std::string_view keyword, std::string_view text) {
  const std::size_t ihdr = kPngSignature.size();
  if (png.size() < ihdr + 12 || png.substr(0, ihdr) != kPngSignature || png.substr(ihdr + 4, 4) != "IHDR")
    throw RuntimeError("PNG stream without a signature and IHDR chunk");
  const std::size_t after_ihdr = ihdr + 12 + get_u32(png, ihdr);
  if (after_ihdr > png.size()) throw RuntimeError("PNG stream cut inside its IHDR chunk");

  const bool ascii = std::all_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
  std::string data(keyword);
  data += '\0';
  if (!ascii) data += std::string("\0\0\0\0", 4);  // no compression, method 0, no language, no translated keyword
  data += text;

  std::string out(png.substr(0, after_ihdr));
  out += png_chunk(ascii ? "tEXt" : "iTXt", data);
  out += png.substr(after_ihdr);
  return out;
}

std::string svg_with_metadata(std::string_view svg, std::string_view text) {
  const auto open = svg.find("<svg");
  const auto end = open == std::string_view::npos ? open : svg.find('>', open);
  if (end == std::string_view::npos) throw RuntimeError("SVG document without an <svg> element");
  std::string out(svg.substr(0, end + 1));
  out += "\n<metadata id=\"provenance\">" + xml_escape(text) + "</metadata>";
  out += svg.substr(end + 1);
  return out;
}

std::string csv_comment(std::string_view text) { return "# " + std::string(text) + "\n"; }

std::string xml_escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace frac::io
