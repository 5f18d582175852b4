#pragma once
// A validating open for files we did not write. libhdf5 1.10 trusts a file's metadata: a corrupt
// global-heap reference of a variable-length string, object header or attribute size can make it read
// out of bounds, allocate gigabytes or loop for ever. Before a reader opens a file, a child process
// (fork) walks everything a reader may touch: every object and link, every attribute (read whole), every
// dataset's type, shape, filters and chunk index, its first element, and every string dataset whole,
// under a memory limit and a watchdog that stops it when it makes no progress for a few seconds. A
// child that fails, crashes or stalls means a damaged file, refused with InputError naming the object
// it was reading. Numeric data beyond the first element is not read: a damaged value is a wrong value or
// a deflate error, which libhdf5 reports.
#include <memory>
#include <string>
#include <vector>

#include "io/hdf5.hpp"

namespace frac::io {

// `name` is the file as messages call it; `image` (when not null) is the file's bytes, for standard input.
// Returns the file's variable-length strings (io/hdf5.hpp, WalkedStrings). InputError for a file
// libhdf5 cannot walk; RuntimeError when the check itself cannot run.
std::shared_ptr<const WalkedStrings> probe_hdf5_file(const std::string& name, const std::vector<char>* image);

}  // namespace frac::io
