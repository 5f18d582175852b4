#include "core/cli.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/signals.hpp"
#include "core/text_file.hpp"
#include "core/version.hpp"

namespace frac::cli {

std::uint64_t parse_seed(const std::string& text, const std::string& option) {
  // (boost would read "-1" as 2^64 - 1)
  const bool digits = !text.empty() && text.size() <= 20 && text.find_first_not_of("0123456789") == std::string::npos;
  errno = 0;
  const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
  if (!digits || errno == ERANGE)
    throw UsageError(option + ": must be a whole number from 0 to 18446744073709551615, got '" + text + "'");
  return v;
}

void check_threads(int threads, const std::string& option) {
  const int most = std::max(256, 4 * static_cast<int>(std::thread::hardware_concurrency()));
  if (threads < 0 || threads > most)
    throw UsageError(option + ": must lie in [0, " + std::to_string(most) + "] (0: all cores), got " +
                     std::to_string(threads));
}

void add_common(po::options_description& desc, CommonOptions& common, unsigned which, const char* output_help) {
  auto add = desc.add_options();
  if (which & kOutput) add("output,o", po::value(&common.output)->default_value("-"), output_help);
  if (which & kSeed)
    add("seed", po::value<std::string>()->default_value("1")->notifier([&common](const std::string& t) {
      common.seed = parse_seed(t, "--seed");
    }),
        "seed of the random generator (0 to 2^64 - 1)");
  if (which & kQuiet) add("quiet,q", po::bool_switch(&common.quiet), "print nothing but errors");
  if (which & kConfig)
    add("config", po::value(&common.config),
        "read options from FILE: 'key = value' lines, key the long option name "
        "(the command line wins)");
  if (which & kThreads)
    add("threads", po::value(&common.threads)->default_value(1)->notifier([](int t) { check_threads(t, "--threads"); }),
        "threads for the force loops (0: all cores); the result does not depend on it. One thread is the "
        "efficient choice when several runs share the machine (make -j); with more, on a busy machine, set "
        "OMP_WAIT_POLICY=passive");
}

namespace {

// What Boost's parsers let through: "-1" for an unsigned option (it wraps to 2^64 - 1) and "nan" or "inf"
// for a floating-point one. `prefix` starts the message ("--config FILE: ").
void check_values(const po::parsed_options& parsed, const po::options_description& desc, const std::string& prefix) {
  for (const auto& o : parsed.options) {
    if (o.unregistered || o.string_key.empty()) continue;
    const po::option_description* d = desc.find_nothrow(o.string_key, false);
    if (!d) continue;
    const po::value_semantic* v = d->semantic().get();
    const bool is_unsigned = dynamic_cast<const po::typed_value<unsigned>*>(v) ||
                             dynamic_cast<const po::typed_value<unsigned long>*>(v) ||
                             dynamic_cast<const po::typed_value<unsigned long long>*>(v);
    const bool is_double = dynamic_cast<const po::typed_value<double>*>(v) != nullptr;
    for (const auto& token : o.value) {
      const auto first = token.find_first_not_of(" \t");
      if (is_unsigned && first != std::string::npos && token[first] == '-')
        throw UsageError(prefix + "--" + o.string_key + ": must not be negative, got '" + token + "'");
      if (is_double) {
        char* end = nullptr;
        const double x = std::strtod(token.c_str(), &end);
        if (end != token.c_str() && !std::isfinite(x))
          throw UsageError(prefix + "--" + o.string_key + ": must be a finite number, got '" + token + "'");
      }
    }
  }
}

// The text of a --config file: a regular file (or a pipe, as from <(...)) of text (core/text_file). A
// directory reads as empty and a device as whatever it gives, which would pass for a file that sets nothing.
std::string read_config_text(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    throw UsageError("--config: cannot read '" + path + "' (" + std::strerror(errno) + ")");
  if (S_ISDIR(st.st_mode)) throw UsageError("--config " + path + ": is a directory, not a file of 'key = value' lines");
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw UsageError("--config " + path + ": not a regular file of 'key = value' lines");
  return read_text_file(path, "the --config file");
}

// The scene keys of a parsed --config file, each once; UsageError for a key that is no option and no
// scene key, a repeated scene key (Boost refuses a repeated option) and 'config' itself (it would be ignored).
std::vector<std::pair<std::string, std::string>> config_scene_keys(const po::parsed_options& parsed,
                                                                   const std::string& path) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const auto& o : parsed.options) {
    if (o.string_key == "config")
      throw UsageError("--config " + path + ": 'config' cannot be set inside a config file (give one --config)");
    if (!o.unregistered) continue;
    if (o.string_key.find('.') == std::string::npos)
      throw UsageError("--config " + path + ": unknown option '" + o.string_key + "'");
    for (const auto& [key, value] : keys)
      if (key == o.string_key) throw UsageError("--config " + path + ": key '" + key + "' is given twice");
    keys.emplace_back(o.string_key, o.value.empty() ? std::string() : o.value.front());
  }
  return keys;
}

// Stores the options of a --config file in vm; its scene keys go to the front of `scene_overrides`
// (when given; else they are unknown options).
void store_config(const std::string& path, po::options_description& desc, po::variables_map& vm,
                  std::vector<std::pair<std::string, std::string>>* scene_overrides) {
  std::istringstream in(read_config_text(path));
  try {
    const auto parsed = po::parse_config_file(in, desc, scene_overrides != nullptr);
    check_values(parsed, desc, "--config " + path + ": ");
    const auto scene_keys = config_scene_keys(parsed, path);
    po::store(parsed, vm);  // skips the unregistered scene keys; keeps what the command line set
    if (scene_overrides) scene_overrides->insert(scene_overrides->begin(), scene_keys.begin(), scene_keys.end());
  } catch (const po::error& e) {
    throw UsageError("--config " + path + ": " + e.what());
  }
}

}  // namespace

po::variables_map parse(int argc, const char* const* argv, const ToolSpec& spec, po::options_description& desc,
                        const po::positional_options_description& positional,
                        std::vector<std::pair<std::string, std::string>>* scene_overrides) {
  po::options_description general("General");
  general.add_options()("help,h", "show this help and exit")("version", "show the version and exit");
  po::options_description all;
  all.add(desc).add(general);

  po::variables_map vm;
  try {
    try {
      const auto parsed = po::command_line_parser(argc, argv).options(all).positional(positional).run();
      check_values(parsed, all, "");
      po::store(parsed, vm);
    } catch (const po::too_many_positional_options_error&) {
      // Name the arguments that are not options: the extra input, or the value of an option that
      // lost its own (a missing value makes the next option's value look like an input).
      const auto loose = po::collect_unrecognized(
          po::command_line_parser(argc, argv).options(all).allow_unregistered().run().options, po::include_positional);
      std::string list;
      for (const auto& a : loose) list += (list.empty() ? "'" : ", '") + a + "'";
      throw UsageError("more arguments than inputs: " + list + " (expected " +
                       std::to_string(positional.max_total_count()) +
                       " input; or an option before them is missing its value)");
    }
    if (vm.count("help")) {
      std::cout << "Usage: " << spec.name << " " << spec.usage << "\n\n"
                << spec.summary << "\n\n"
                << all << "\nExample:\n"
                << spec.example << "\n";
      throw Exit{kExitOk};
    }
    if (vm.count("version")) {
      std::cout << spec.name << " " << kVersion << " (file format " << kFormatMajor << "." << kFormatMinor << ")\n";
      throw Exit{kExitOk};
    }
    if (vm.count("config")) store_config(vm["config"].as<std::string>(), desc, vm, scene_overrides);
    po::notify(vm);
  } catch (const po::invalid_command_line_syntax& e) {
    // Boost's "the required argument for option '--steps' is missing": say which, first.
    if (e.kind() == po::invalid_syntax::missing_parameter) throw UsageError(e.get_option_name() + ": missing value");
    throw UsageError(e.what());
  } catch (const po::required_option& e) {
    // A positional argument is "required" under a name the command line never shows ("--input").
    const std::string& option = e.get_option_name();
    const std::string name = option.substr(std::min(option.size(), option.find_first_not_of('-')));
    for (unsigned k = 0; k < positional.max_total_count() && k < 16; ++k)
      if (positional.name_for_position(k) == name)
        throw UsageError("no " + name + " given (usage: " + spec.name + " " + spec.usage + ")");
    throw UsageError(e.get_option_name() + ": missing (required)");
  } catch (const po::error& e) {
    throw UsageError(e.what());
  }
  return vm;
}

std::vector<const char*> split_overrides(int argc, const char* const* argv,
                                         std::vector<std::pair<std::string, std::string>>& overrides) {
  std::vector<const char*> rest;
  const std::size_t first = overrides.size();
  for (int k = 0; k < argc; ++k) {
    const std::string arg = argv[k];
    const bool dotted = k > 0 && arg.rfind("--", 0) == 0 && arg.find('.') != std::string::npos &&
                        arg.find('.') < arg.find('=') && std::isalpha(static_cast<unsigned char>(arg[2]));
    if (!dotted) {
      rest.push_back(argv[k]);
      continue;
    }
    const auto eq = arg.find('=');
    std::pair<std::string, std::string> o;
    if (eq != std::string::npos) {
      o = {arg.substr(2, eq - 2), arg.substr(eq + 1)};
    } else {
      if (k + 1 >= argc) throw UsageError(arg + ": needs a value");
      o = {arg.substr(2), argv[++k]};
    }
    // (a repeated key would silently take its last value)
    for (auto it = overrides.begin() + static_cast<std::ptrdiff_t>(first); it != overrides.end(); ++it)
      if (it->first == o.first)
        throw UsageError("--" + o.first + ": given twice on the command line ('" + it->second + "', then '" + o.second +
                         "')");
    overrides.push_back(std::move(o));
  }
  return rest;
}

namespace {

const std::string* g_tool = nullptr;

// An exception that leaves a parallel region (OpenMP ends the program): the message and exit 1 all the same,
// after the cleanup hooks (the temporaries removed), rather than an abort.
[[noreturn]] void on_terminate() {
  std::string what = "internal error (an exception in a thread)";
  try {
    if (const std::exception_ptr e = std::current_exception()) std::rethrow_exception(e);
  } catch (const std::bad_alloc&) {
    what = out_of_memory().what();
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
  }
  std::fflush(stdout);
  std::cerr << (g_tool ? *g_tool : std::string("fracture")) << ": error: " << what << std::endl;
  run_cleanup_hooks();
  _exit(kExitRuntime);
}

}  // namespace

int run_tool(const std::string& tool, const std::function<int()>& body) {
  g_tool = &tool;
  std::set_terminate(on_terminate);
  // Past a file size limit (ulimit -f) a write fails with EFBIG, reported with the file's name, instead of
  // the signal ending the process with no word and its temporaries left.
  std::signal(SIGXFSZ, SIG_IGN);
  auto fail = [&](const char* what, int code) {
    std::fflush(stdout);
    std::cout.flush();
    std::cerr << tool << ": error: " << what << "\n";
    if (code == kExitBadInput) std::cerr << "Try '" << tool << " --help'.\n";
    return code;
  };
  int code = kExitOk;
  try {
    try {
      code = body();
    } catch (const Exit& e) {
      code = e.code;
    }
    // A full disk or a closed pipe behind standard output shows only here, in the buffered tail or the
    // stream's error flag: a tool whose output was lost must not exit 0.
    std::cout.flush();
    const bool written = std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good();
    if (!written) throw RuntimeError(std::string("-: cannot write to standard output (") + std::strerror(errno) + ")");
    return code;
  } catch (const Interrupted& e) {
    std::fflush(stdout);
    std::cout.flush();
    std::cerr << tool << ": " << e.what() << "\n";
    die_by_signal(e.signal);
  } catch (const UsageError& e) {
    return fail(e.what(), kExitBadInput);
  } catch (const InputError& e) {
    return fail(e.what(), kExitBadInput);
  } catch (const po::error& e) {
    return fail(e.what(), kExitBadInput);
  } catch (const std::bad_alloc&) {
    return fail(out_of_memory().what(), kExitRuntime);
  } catch (const std::exception& e) {
    return fail(e.what(), kExitRuntime);
  }
}

int run_subcommands(const std::string& tool, int argc, const char* const* argv,
                    const std::map<std::string, std::pair<std::string, Subcommand>>& table) {
  return run_tool(tool, [&]() -> int {
    const std::string first = argc > 1 ? argv[1] : "";
    if (first == "--version") {
      std::cout << tool << " " << kVersion << " (file format " << kFormatMajor << "." << kFormatMinor << ")\n";
      return kExitOk;
    }
    if (first.empty() || first == "--help" || first == "-h") {
      std::ostream& out = first.empty() ? std::cerr : std::cout;
      out << "Usage: " << tool << " COMMAND [options]\n\nCommands:\n";
      for (const auto& [name, entry] : table)
        out << "  " << name << std::string(14 - std::min<std::size_t>(13, name.size()), ' ') << entry.first << "\n";
      out << "\n'" << tool << " COMMAND --help' describes a command, with an example.\n";
      return first.empty() ? kExitBadInput : kExitOk;
    }
    const auto it = table.find(first);
    if (it == table.end()) throw UsageError("unknown command '" + first + "'");
    return it->second.second(argc - 1, argv + 1, command_line(argc, argv));
  });
}

std::string command_line(int argc, const char* const* argv) {
  std::string out;
  for (int k = 0; k < argc; ++k) {
    const std::string arg = argv[k];
    if (k) out += ' ';
    const bool plain =
        !arg.empty() &&
        arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,+@%") ==
            std::string::npos;
    if (plain) {
      out += arg;
    } else {
      out += '\'';
      for (char c : arg) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
      out += '\'';
    }
  }
  return out;
}

namespace {
template <class T>
std::array<T, 2> parse_pair(const std::string& text, const std::string& option) {
  const auto x = text.find_first_of("xX");
  std::array<T, 2> out{};
  bool ok = x != std::string::npos && x > 0 && x + 1 < text.size();
  for (int k = 0; ok && k < 2; ++k) {
    const std::string part = k == 0 ? text.substr(0, x) : text.substr(x + 1);
    std::istringstream in(part);
    in >> out[k];
    ok = static_cast<bool>(in) && in.peek() == std::char_traits<char>::eof();
  }
  if (!ok) throw UsageError(option + ": expected two values written AxB, got '" + text + "'");
  return out;
}
}  // namespace

std::array<double, 2> parse_pair_double(const std::string& text, const std::string& option) {
  return parse_pair<double>(text, option);
}
std::array<std::int64_t, 2> parse_pair_int(const std::string& text, const std::string& option) {
  return parse_pair<std::int64_t>(text, option);
}

std::set<std::string> given_options(const po::variables_map& vm) {
  std::set<std::string> given;
  for (const auto& [key, value] : vm)
    if (!value.defaulted()) given.insert(key);
  return given;
}

std::vector<std::pair<std::string, std::string>> resolved_options(const po::variables_map& vm) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [key, value] : vm) {
    if (key == "help" || key == "version" || key == "output" || key == "quiet" || key == "config") continue;
    const auto& v = value.value();
    std::ostringstream text;
    text.precision(17);
    if (const auto* s = boost::any_cast<std::string>(&v))
      text << *s;
    else if (const auto* d = boost::any_cast<double>(&v))
      text << *d;
    else if (const auto* i = boost::any_cast<int>(&v))
      text << *i;
    else if (const auto* l = boost::any_cast<long>(&v))
      text << *l;
    else if (const auto* ll = boost::any_cast<long long>(&v))
      text << *ll;
    else if (const auto* u = boost::any_cast<unsigned long>(&v))
      text << *u;
    else if (const auto* b = boost::any_cast<bool>(&v))
      text << (*b ? "true" : "false");
    else if (const auto* vs = boost::any_cast<std::vector<std::string>>(&v)) {
      for (std::size_t k = 0; k < vs->size(); ++k) text << (k ? " " : "") << (*vs)[k];
    } else
      text << "?";
    out.emplace_back(key, text.str());
  }
  return out;
}

}  // namespace frac::cli
