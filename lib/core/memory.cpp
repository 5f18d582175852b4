#include "core/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <new>

namespace frac {
namespace {

thread_local std::size_t g_failed_bytes = 0;  // the last request operator new could not serve

std::string bytes_text(double bytes) {
  if (bytes < 1e3) return std::to_string(static_cast<long long>(bytes)) + " bytes";
  char text[32];
  const char* unit = bytes >= 1e9 ? "GB" : bytes >= 1e6 ? "MB" : "kB";
  const double scale = bytes >= 1e9 ? 1e9 : bytes >= 1e6 ? 1e6 : 1e3;
  std::snprintf(text, sizeof text, "%.3g %s", bytes / scale, unit);
  return text;
}

std::string limit_text() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    return "the process may use " + bytes_text(static_cast<double>(limit.rlim_cur)) + ": ulimit -v";
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0)
    return "the machine has " + bytes_text(static_cast<double>(pages) * static_cast<double>(page));
  return "the memory of the machine";
}

std::string message(const std::string& what, std::size_t bytes) {
  return "out of memory: " + what + (bytes > 0 ? " needs " + bytes_text(static_cast<double>(bytes)) + " more" : "") +
         " (" + limit_text() + ")";
}

}  // namespace

OutOfMemory::OutOfMemory(const std::string& what, std::size_t bytes) : RuntimeError(message(what, bytes)) {}

OutOfMemory out_of_memory(const std::string& what) {
  const std::size_t bytes = g_failed_bytes;
  g_failed_bytes = 0;
  return OutOfMemory(what, bytes);
}

}  // namespace frac

// The replaceable allocation function, to record the size of a request that fails (out_of_memory names it).
// Not under AddressSanitizer, which must see every allocation as its own.
#if !defined(__SANITIZE_ADDRESS__)
void* operator new(std::size_t bytes) {
  for (;;) {
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) {
      frac::g_failed_bytes = bytes;
      throw std::bad_alloc();
    }
    handler();
  }
}
#endif
