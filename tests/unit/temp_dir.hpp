#pragma once
// A fresh folder for a test's files: <temporary folder>/fracture-test-<name>-<8 random hex digits>.
#include <filesystem>
#include <string>

#include "core/provenance.hpp"

namespace frac::test {

inline std::filesystem::path temp_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("fracture-test-" + name + "-" + make_uuid().substr(0, 8));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace frac::test
