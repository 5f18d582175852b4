#include "io/hdf5_image.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace frac::io {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
constexpr std::uint64_t kUndefined = ~std::uint64_t{0};

// Reads up to `size` more bytes into `out`; fewer only at the end of the stream.
void read_more(std::FILE* in, std::vector<char>& out, std::size_t size, const std::string& name) {
  const std::size_t start = out.size();
  out.resize(start + size);
  const std::size_t got = std::fread(out.data() + start, 1, size, in);
  if (got < size && std::ferror(in)) throw InputError(name + ": cannot read (" + std::strerror(errno) + ")");
  out.resize(start + got);
}

std::uint64_t little_endian(const std::vector<char>& b, std::size_t at, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < bytes; ++k) v |= std::uint64_t{static_cast<unsigned char>(b[at + k])} << (8 * k);
  return bytes < 8 && v == (std::uint64_t{1} << (8 * bytes)) - 1 ? kUndefined : v;
}

// The end-of-file address of the superblock at the start of `b` (format versions 0 to 3), or kUndefined
// when it is not yet read far enough (`need` then says how far) or not recorded.
std::uint64_t end_of_file(const std::vector<char>& b, std::size_t& need) {
  const int version = static_cast<unsigned char>(b[8]);
  const std::size_t offsets = static_cast<unsigned char>(b[version < 2 ? 13 : 9]);
  if (offsets != 2 && offsets != 4 && offsets != 8) return kUndefined;
  const std::size_t base = version == 0 ? 24 : version == 1 ? 28 : 12;
  const std::size_t at = base + 2 * offsets;  // after the base and free-space (or extension) addresses
  need = at + offsets;
  if (b.size() < need) return kUndefined;
  const std::uint64_t base_address = little_endian(b, base, offsets), eof = little_endian(b, at, offsets);
  if (base_address != 0 || eof == kUndefined) return kUndefined;
  return eof;
}

}  // namespace

std::shared_ptr<std::vector<char>> read_hdf5_image(std::FILE* in, const std::string& name) {
  const std::string what = name == "-" ? "-: standard input" : name;
  auto image = std::make_shared<std::vector<char>>();
  read_more(in, *image, 64, what);
  if (image->empty()) throw InputError(what + " is empty (expected an HDF5 file)");
  if (image->size() < sizeof kSignature || std::memcmp(image->data(), kSignature, sizeof kSignature) != 0)
    throw InputError(what + " is not an HDF5 file");
  std::size_t need = 0;
  const std::uint64_t eof = image->size() > 13 ? end_of_file(*image, need) : kUndefined;
  if (eof != kUndefined && eof < image->size())
    throw InputError(what + ": damaged HDF5 superblock (it gives a length of " + std::to_string(eof) + " bytes)");
  if (eof != kUndefined) {
    const std::size_t rest = static_cast<std::size_t>(eof) - image->size();
    try {
      image->reserve(static_cast<std::size_t>(eof));
    } catch (const std::bad_alloc&) {
      throw OutOfMemory("reading " + what, static_cast<std::size_t>(eof));
    } catch (const std::length_error&) {
      throw InputError(what + ": the superblock gives an impossible length (" + std::to_string(eof) + " bytes)");
    }
    read_more(in, *image, rest, what);
    if (image->size() < eof)
      throw InputError(what + ": truncated HDF5 file (" + std::to_string(image->size()) + " of " + std::to_string(eof) +
                       " bytes)");
    return image;
  }
  // No length recorded (a file still being written): to the end of the stream.
  try {
    for (std::size_t before = 0; before != image->size();) {
      before = image->size();
      read_more(in, *image, std::size_t{1} << 20, what);
    }
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("reading " + what, image->size());
  }
  return image;
}

}  // namespace frac::io
