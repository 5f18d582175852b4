#pragma once
// Running out of memory, as a message that names what was being allocated and its size, and the limit that
// was met (ulimit -v, or the machine's memory): exit 1, never "damaged file" or a bare std::bad_alloc.
#include <cstddef>
#include <string>

#include "core/error.hpp"

namespace frac {

struct OutOfMemory : RuntimeError {
  // "out of memory: <what> needs <bytes> more (the process may use 2.0 GB: ulimit -v)"; bytes 0: not known.
  OutOfMemory(const std::string& what, std::size_t bytes);
};

// The error for a std::bad_alloc just caught while allocating `what` ("the DEM model of 1000000 cells"), with
// the size of the request that failed (the tools replace operator new to record it).
OutOfMemory out_of_memory(const std::string& what = "an allocation");

}  // namespace frac
