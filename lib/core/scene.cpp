#include "core/scene.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace frac {
namespace po = boost::program_options;

namespace {
std::string format_number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}
}  // namespace

Scene Scene::parse(const std::string& text, const std::string& name) {
  Scene scene;
  scene.name_ = name;
  scene.source_ = text;
  std::istringstream in(text);
  try {
    po::options_description none;
    const auto parsed = po::parse_config_file(in, none, /*allow_unregistered=*/true);
    for (const auto& opt : parsed.options) {
      if (opt.string_key.find('.') == std::string::npos)
        throw InputError(name + ": key '" + opt.string_key + "' is outside a [section]");
      if (opt.value.size() != 1) throw InputError(name + ": key '" + opt.string_key + "' has no value");
      if (scene.values_.count(opt.string_key)) throw InputError(name + ": key '" + opt.string_key + "' is given twice");
      scene.values_[opt.string_key] = opt.value.front();
    }
  } catch (const po::error& e) {
    throw InputError(name + ": " + e.what());
  }
  return scene;
}

Scene Scene::load(const std::string& path) {
  Scene scene = parse(read_text_file(path, "the scene file"), path);
  // An empty file (a truncated copy, a wrong path to /dev/null) would run on defaults alone.
  if (scene.values_.empty()) throw InputError(path + ": the scene file sets no keys (an empty scene)");
  return scene;
}

Scene Scene::load(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides) {
  Scene scene = load(path);
  for (const auto& [key, value] : overrides) scene.set(key, value);
  return scene;
}

void Scene::set(const std::string& key, const std::string& value) {
  values_[key] = value;
  overridden_.insert(key);
}

std::string Scene::origin(std::string_view key) const {
  if (overridden_.count(key)) return "--" + std::string(key);
  return name_ + ": " + std::string(key);
}

bool Scene::has(std::string_view key) const { return values_.find(key) != values_.end(); }

const std::string* Scene::find(std::string_view key) {
  auto it = values_.find(key);
  return it == values_.end() ? nullptr : &it->second;
}

void Scene::bad(std::string_view key, const std::string& value, const std::string& why) const {
  throw UsageError(origin(key) + " = '" + value + "': " + why);
}

double Scene::number(std::string_view key, double fallback) {
  double x = fallback;
  if (const std::string* v = find(key)) {
    const char* b = v->data();
    const char* e = b + v->size();
    while (b < e && *b == ' ') ++b;
    auto [p, ec] = std::from_chars(b, e, x);
    while (p < e && *p == ' ') ++p;
    if (ec != std::errc() || p != e) bad(key, *v, "not a number");
    if (!std::isfinite(x)) bad(key, *v, "not finite");
  }
  resolved_[std::string(key)] = format_number(x);
  return x;
}

double Scene::number(std::string_view key) {
  if (!has(key)) throw UsageError(name_ + ": " + std::string(key) + " is required");
  return number(key, 0.0);
}

double Scene::positive(std::string_view key, double fallback) {
  const double x = number(key, fallback);
  if (!(x > 0)) bad(key, resolved_[std::string(key)], "must be positive");
  return x;
}

double Scene::non_negative(std::string_view key, double fallback) {
  const double x = number(key, fallback);
  if (!(x >= 0)) bad(key, resolved_[std::string(key)], "must not be negative");
  return x;
}

double Scene::in(std::string_view key, double fallback, const Interval& range) {
  const double x = number(key, fallback);
  if (!range.contains(x)) {
    const std::string* given = find(key);  // as written: 1e300, not 1.0000000000000001e+300
    const bool sign = range.lo == 0 && !(range.lo_open ? x > 0 : x >= 0);  // the messages of positive(), non_negative()
    bad(key, given ? *given : resolved_[std::string(key)],
        sign ? (range.lo_open ? "must be positive" : "must not be negative") : "must lie in " + range.text());
  }
  return x;
}

void Scene::refuse(std::string_view key, const std::string& why) const {
  const auto given = values_.find(key);
  const auto read = resolved_.find(key);
  bad(key, given != values_.end() ? given->second : read != resolved_.end() ? read->second : "", why);
}

void Scene::require(std::string_view key, const std::string& what) const {
  if (!has(key)) throw UsageError(name_ + ": " + std::string(key) + " is required (" + what + ")");
}

long long Scene::integer(std::string_view key, long long fallback) {
  long long x = fallback;
  if (const std::string* v = find(key)) {
    auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), x);
    if (ec != std::errc() || p != v->data() + v->size()) {
      // Accept integral values written as numbers, e.g. 1e6.
      const double d = number(key, 0.0);
      if (d != std::floor(d) || std::abs(d) > 9e15) bad(key, *v, "not an integer");
      x = static_cast<long long>(d);
    }
  }
  resolved_[std::string(key)] = std::to_string(x);
  return x;
}

bool Scene::flag(std::string_view key, bool fallback) {
  bool x = fallback;
  if (const std::string* v = find(key)) {
    if (*v == "on" || *v == "true" || *v == "yes" || *v == "1")
      x = true;
    else if (*v == "off" || *v == "false" || *v == "no" || *v == "0")
      x = false;
    else
      bad(key, *v, "expected on or off");
  }
  resolved_[std::string(key)] = x ? "on" : "off";
  return x;
}

std::string Scene::text(std::string_view key, const std::string& fallback) {
  const std::string* v = find(key);
  std::string x = v ? *v : fallback;
  resolved_[std::string(key)] = x;
  return x;
}

std::string Scene::choice(std::string_view key, const std::string& fallback, const std::vector<std::string>& choices) {
  const std::string x = text(key, fallback);
  for (const auto& c : choices)
    if (c == x) return x;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  bad(key, x, "expected one of " + list);
}

std::vector<std::string> Scene::subset(std::string_view key, const std::vector<std::string>& choices) {
  std::string all;
  for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
  const std::string x = text(key, all);
  std::vector<bool> chosen(choices.size(), false);
  std::istringstream in(x);
  for (std::string name; std::getline(in, name, ',');) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    const auto it = std::find(choices.begin(), choices.end(), name);
    if (it == choices.end()) bad(key, x, "'" + name + "' is not one of " + all);
    if (chosen[static_cast<std::size_t>(it - choices.begin())]) bad(key, x, "'" + name + "' is named twice");
    chosen[static_cast<std::size_t>(it - choices.begin())] = true;
  }
  std::vector<std::string> out;
  for (std::size_t k = 0; k < choices.size(); ++k)
    if (chosen[k]) out.push_back(choices[k]);
  return out;
}

std::vector<std::pair<std::string, std::string>> Scene::resolved() const {
  return {resolved_.begin(), resolved_.end()};
}

void Scene::check_all_used() const {
  std::string in_file, in_options;
  for (const auto& [k, v] : values_) {
    if (resolved_.count(k)) continue;
    std::string& list = overridden_.count(k) ? in_options : in_file;
    list += (list.empty() ? "" : ", ") + k;
  }
  if (!in_file.empty()) throw UsageError(name_ + ": unknown key(s): " + in_file);
  if (!in_options.empty()) throw UsageError("scene options (command line or --config): unknown key(s): " + in_options);
}

}  // namespace frac
