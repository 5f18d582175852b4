#include "core/text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.hpp"

namespace frac {

std::string read_text_file(const std::string& path, const std::string& what, std::size_t max_bytes) {
  const bool standard_input = path == "-";
  const std::string name = standard_input ? "-" : path;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(standard_input ? stdin : std::fopen(path.c_str(), "rb"),
                                                       standard_input ? [](std::FILE*) { return 0; } : std::fclose);
  if (!file) throw InputError(name + ": cannot read " + what + " (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[1 << 14];
  for (;;) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    if (std::memchr(buffer, '\0', n)) throw InputError(name + ": " + what + " holds a NUL byte: not a text file");
    text.append(buffer, n);
    if (text.size() > max_bytes)
      throw InputError(name + ": " + what + " is longer than " + std::to_string(max_bytes) + " bytes");
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get()))
    throw InputError(name + ": cannot read " + what + " (" + (errno == EISDIR ? "a folder" : std::strerror(errno)) +
                     ")");
  return text;
}

}  // namespace frac
