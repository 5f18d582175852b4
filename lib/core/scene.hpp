#pragma once
// A scene file: INI sections ([material], [physics], [loading], [integrator], [stop], [output], ...)
// of "key = value" lines, read with Boost.Program_options, plus command-line overrides
// ("--material.beam_modulus 1e9"). Values are read through typed getters that record what was
// resolved (defaults included) for the run's /parameters; keys the model never read are refused at
// the end (a typo in a scene never passes silently). Keys are "section.key".
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/option_check.hpp"

namespace frac {

class Scene {
 public:
  Scene() = default;
  // InputError naming the file (and line, where Boost tells it) for an unreadable or malformed file.
  static Scene load(const std::string& path);
  // The file, then the command-line overrides ({"section.key", "value"}, from cli::split_overrides).
  static Scene load(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides);
  static Scene parse(const std::string& text, const std::string& name);
  // Command-line overrides win over the file. Messages about an overridden key name the option, not the file.
  void set(const std::string& key, const std::string& value);

  bool has(std::string_view key) const;
  // Getters: the value, or the default when the key is absent; UsageError naming the key and the
  // scene when the value does not parse or is out of range.
  double number(std::string_view key, double fallback);
  double number(std::string_view key);                                      // required
  double positive(std::string_view key, double fallback);                   // > 0
  double non_negative(std::string_view key, double fallback);               // >= 0
  double in(std::string_view key, double fallback, const Interval& range);  // finite, in `range`
  long long integer(std::string_view key, long long fallback);
  bool flag(std::string_view key, bool fallback);  // on|off|true|false|yes|no|1|0
  std::string text(std::string_view key, const std::string& fallback);
  // One of `choices`.
  std::string choice(std::string_view key, const std::string& fallback, const std::vector<std::string>& choices);
  // Some of `choices`, comma-separated, each once, in the order of `choices` (default: all of them).
  std::vector<std::string> subset(std::string_view key, const std::vector<std::string>& choices);

  // UsageError naming the scene unless `key` is given (in the file or as an override); `what` says what
  // it decides ("what the run does").
  void require(std::string_view key, const std::string& what) const;
  // UsageError naming `key` (where it was given) and its value as written, with `why`: for checks of a value
  // against others that the getters cannot make.
  [[noreturn]] void refuse(std::string_view key, const std::string& why) const;

  // Every key read so far with its resolved value (text), sorted.
  std::vector<std::pair<std::string, std::string>> resolved() const;
  // UsageError naming every key of the file or the overrides that nothing read.
  void check_all_used() const;
  const std::string& name() const { return name_; }
  // The scene file as read, verbatim (recorded in the run's /parameters).
  const std::string& source_text() const { return source_; }

 private:
  const std::string* find(std::string_view key);
  [[noreturn]] void bad(std::string_view key, const std::string& value, const std::string& why) const;
  // A key as a message names it: "SCENE.ini: key" from the file, "--key" from an override.
  std::string origin(std::string_view key) const;
  std::string name_ = "scene";
  std::string source_;
  std::map<std::string, std::string, std::less<>> values_;
  std::map<std::string, std::string, std::less<>> resolved_;
  std::set<std::string, std::less<>> overridden_;
};

}  // namespace frac
