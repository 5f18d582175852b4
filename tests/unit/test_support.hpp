#pragma once
// What several unit tests share: a fresh folder for a test's files, and a thread count for a scope. Of the core
// layer only, so that the tests of every layer may include it (small meshes: mesh_test_support.hpp).
#include <filesystem>
#include <string>

#include "core/parallel.hpp"
#include "core/provenance.hpp"

namespace frac::test {

// <temporary folder>/fracture-test-<name>-<8 random hex digits>, created.
inline std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("fracture-test-" + name + "-" + make_uuid().substr(0, 8));
  std::filesystem::create_directories(dir);
  return dir;
}

// The thread count of the force loops' teams (frac::set_threads: `threads`, or every core for 0) while the guard
// lives, and the count before it back when it goes, however the scope is left (an ASSERT_ or GTEST_SKIP returns
// from the test early): one test's count does not leak into the tests after it in the same process.
//   for (const int threads : {1, 2, 3}) {
//     const test::ThreadCount thread_count(threads);
//     ...
//   }
// (set_threads also puts the threads in the simulation's floating-point mode, core/float_mode.hpp: that stays.)
class ThreadCount {
 public:
  explicit ThreadCount(int threads) : before_(max_threads()) { set_threads(threads); }
  ~ThreadCount() { set_threads(before_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int before_;
};

}  // namespace frac::test
