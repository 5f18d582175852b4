#pragma once
// Copies a group of one HDF5 file into another: its datasets chunk by chunk as they are stored (compressed
// chunks are not decoded), its attributes and its subgroups. A checkpoint's copy of the output so far. libhdf5's
// own H5Ocopy crashes (1.10.8) when a write fails on a full disk: here a failed write is an error like any other.
#include <string>

#include "io/hdf5.hpp"

namespace frac::io {

// Copies the group at `path` under `from` to the same path under `to` (its parents created): RuntimeError
// naming the copy and the cause (write_failure) when a write fails.
void copy_group(const Group& from, const std::string& path, Group& to);

}  // namespace frac::io
