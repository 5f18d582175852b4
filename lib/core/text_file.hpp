#pragma once
// Small text inputs (a scene, a --config file) read whole, but bounded: a device such as /dev/zero, a FIFO
// that never ends or a binary file is refused after at most `max_bytes`, never read until memory runs out.
#include <cstddef>
#include <string>

namespace frac {

inline constexpr std::size_t kMaxSceneBytes = std::size_t{1} << 20;

// The text of `path` ("-": standard input). InputError naming `path` and `what` ("the scene file") when it
// cannot be opened, is a folder, holds a NUL byte (not text) or is longer than `max_bytes`.
std::string read_text_file(const std::string& path, const std::string& what, std::size_t max_bytes = kMaxSceneBytes);

}  // namespace frac
