#pragma once
// Provenance in the outputs that have no /provenance group (docs/SCHEMA.md): the line of
// frac::provenance_line as a PNG text chunk, an SVG <metadata> element, the first line of a CSV table
// and an XDMF Information element.
#include <string>
#include <string_view>

namespace frac::io {

// Keyword of the PNG text chunk and name of the XDMF Information element.
inline constexpr std::string_view kProvenanceKey = "provenance";

// The PNG stream `png` with a text chunk (keyword, text) right after IHDR: tEXt, or iTXt (UTF-8) when
// `text` is not plain ASCII, since tEXt is Latin-1. RuntimeError when `png` does not start with IHDR.
std::string png_with_text(std::string_view png, std::string_view keyword, std::string_view text);

// The SVG document with <metadata id="provenance">text</metadata> as the first child of <svg>.
// RuntimeError when there is no <svg> element.
std::string svg_with_metadata(std::string_view svg, std::string_view text);

// "# text\n": the first line of a CSV table or of `key value` lines (gnuplot and awk '$1 == "key"' skip it;
// other readers: grep -v '^#').
std::string csv_comment(std::string_view text);

// & < > " as entities: for XML element content and attribute values.
std::string xml_escape(std::string_view text);

}  // namespace frac::io
