#include "core/file_roles.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "core/error.hpp"

namespace frac {
namespace {

// What a path names: the file's device and inode when it exists, else its absolute path with "." and ".."
// and the symbolic links of its folders resolved (two new outputs are one file when these agree).
struct Identity {
  bool exists = false;
  bool device = false;  // a character device
  dev_t dev = 0;
  ino_t ino = 0;
  std::string name;
};

Identity identify(const std::string& path, bool input) {
  Identity id;
  struct stat st {};
  if (path == "-") {
    id.name = input ? "<standard input>" : "<standard output>";
    if (fstat(input ? STDIN_FILENO : STDOUT_FILENO, &st) != 0) return id;
  } else {
    std::error_code ec;
    const auto resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    id.name = ec ? path : resolved.string();
    if (stat(path.c_str(), &st) != 0) return id;
  }
  id.exists = true;
  id.device = S_ISCHR(st.st_mode);
  id.dev = st.st_dev;
  id.ino = st.st_ino;
  return id;
}

bool same(const Identity& a, const Identity& b) {
  if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
  return a.name == b.name;
}

std::string named(const FileRole& f, bool input) {
  return f.role + " " + (f.path != "-" ? "'" + f.path + "'" : input ? "- (standard input)" : "- (standard output)");
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  const Identity x = identify(a, true), y = identify(b, true);
  return x.exists && y.exists && same(x, y);
}

void check_file_roles(const std::vector<FileRole>& inputs, const std::vector<FileRole>& outputs) {
  std::vector<Identity> in, out;
  for (const FileRole& f : inputs) in.push_back(identify(f.path, true));
  for (const FileRole& f : outputs) out.push_back(identify(f.path, false));
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    if (outputs[o].path.empty() || out[o].device) continue;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      // (standard input and output are two streams unless both are one regular file)
      if (inputs[i].path.empty() || !in[i].exists || !out[o].exists || !same(in[i], out[o])) continue;
      throw UsageError(named(outputs[o], false) + " is the input " + named(inputs[i], true) +
                       ": writing it would replace the input; give the output another name");
    }
    for (std::size_t p = 0; p < o; ++p)
      if (!outputs[p].path.empty() && !out[p].device && same(out[p], out[o]))
        throw UsageError(named(outputs[p], false) + " and " + named(outputs[o], false) +
                         " are one file: one output would replace the other; give them different names");
  }
}

}  // namespace frac
