#pragma once
// An HDF5 file read from a stream (standard input, a FIFO, a device) into memory, as HDF5 cannot seek in
// one. Bounded: the signature is checked after 8 bytes (/dev/zero is refused at once), and the superblock
// gives the file's length, which is read exactly and allocated once.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace frac::io {

// The file image on `in`, named `name` in messages ("-" reads as "standard input"). InputError when the
// stream is empty, not HDF5 or shorter than its superblock says; OutOfMemory when the image does not fit.
std::shared_ptr<std::vector<char>> read_hdf5_image(std::FILE* in, const std::string& name);

}  // namespace frac::io
