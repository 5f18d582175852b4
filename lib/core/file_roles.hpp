#pragma once
// The files a tool reads and writes, by the role the command line gives them ("MESH", "--scene", "-o"). No
// output may be one of the inputs, nor two outputs one file: the same path, "./path", a symbolic or a hard
// link (the same device and inode), standard input or output redirected from or to that file. Checked
// before any work, so that a slip of the keyboard never replaces a mesh or a week's run.
#include <string>
#include <vector>

namespace frac {

struct FileRole {
  std::string role;  // as the command line names it: "MESH", "--scene", "-o"
  std::string path;  // "-": standard input (an input) or standard output (an output); "": none, skipped
};

// UsageError naming both roles and paths when an output is one of the inputs, or two outputs one file
// (character devices such as /dev/null excepted: writing one twice loses nothing).
void check_file_roles(const std::vector<FileRole>& inputs, const std::vector<FileRole>& outputs);

// Whether two paths name one existing file (device and inode; "-" is standard input).
bool same_file(const std::string& a, const std::string& b);

}  // namespace frac
