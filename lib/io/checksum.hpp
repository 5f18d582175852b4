#pragma once
// FNV-1a over 8-byte words (the tail byte by byte): a running checksum that detects damaged data at memory
// speed (checkpoints: the state and the output so far). Not a cryptographic hash.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace frac::io {

struct Checksum {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t k = 0;
    for (; k + 8 <= bytes; k += 8) {
      std::uint64_t w;
      std::memcpy(&w, p + k, 8);
      h = (h ^ w) * 0x100000001b3ull;
    }
    for (; k < bytes; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
  }
  template <class T>
  void add_value(const T& x) {
    add(&x, sizeof x);
  }
};

}  // namespace frac::io
