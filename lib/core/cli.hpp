#pragma once
// Command-line conventions shared by every tool: common options declared once, --help with an
// example, --version, --config FILE, and one exit path that maps exceptions to exit codes
// (0 success, 2 bad usage or input, 1 runtime failure) with "tool: error: message" on stderr.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <boost/program_options.hpp>

namespace frac::cli {

namespace po = boost::program_options;

// What a tool (or one of its subcommands) says about itself in --help.
struct ToolSpec {
  std::string name;     // "mesh-gen voronoi"
  std::string usage;    // "[options] -o OUT"
  std::string summary;  // one paragraph
  std::string example;  // one or more example command lines
};

// Options most tools share; each tool picks the ones it needs.
struct CommonOptions {
  std::string output = "-";
  bool quiet = false;
  std::uint64_t seed = 1;
  std::string config;
  int threads = 1;  // 0: all cores
};
enum Common : unsigned { kOutput = 1, kQuiet = 2, kSeed = 4, kConfig = 8, kThreads = 16 };
// `output_help` describes -o for a tool whose output is not (only) an HDF5 file.
inline constexpr const char* kOutputHdf5OrText =
    "output file; '-' writes standard output: the HDF5 file, or with --format text the key value lines";
void add_common(po::options_description& desc, CommonOptions& common, unsigned which,
                const char* output_help = "output file; '-' writes the HDF5 file to standard output");

// Thrown to end a tool early with an exit code (after --help or --version).
struct Exit {
  int code;
};

// Parse argv into vm (notifying the bound variables). Handles --help and --version (throws Exit{0})
// and --config FILE (a regular text file or a pipe: the same options, one "key = value" a line, each key
// once and never 'config' itself; a key on the command line too takes the command line's value). Throws
// UsageError on bad options. With `scene_overrides` (the command line's, from split_overrides), the
// file may also hold scene keys, "section.key = value" or "key = value" under "[section]": they go
// before the command line's, which win.
po::variables_map parse(int argc, const char* const* argv, const ToolSpec& spec, po::options_description& desc,
                        const po::positional_options_description& positional = {},
                        std::vector<std::pair<std::string, std::string>>* scene_overrides = nullptr);

// Splits scene overrides out of argv: every "--section.key VALUE" or "--section.key=VALUE" (a dotted
// option name) goes to `overrides` as {"section.key", "VALUE"}; the rest stays in the returned argv
// (argv[0] first) for parse(). UsageError for a dotted option without a value, or given twice.
std::vector<const char*> split_overrides(int argc, const char* const* argv,
                                         std::vector<std::pair<std::string, std::string>>& overrides);

// Runs a tool body and maps exceptions to exit codes; flushes stdout before printing errors.
int run_tool(const std::string& tool, const std::function<int()>& body);

// A tool with subcommands: argv[1] picks the body from the table, which gets argc-1, argv+1 and the
// full command line (for provenance).
using Subcommand = std::function<int(int, const char* const*, const std::string&)>;
int run_subcommands(const std::string& tool, int argc, const char* const* argv,
                    const std::map<std::string, std::pair<std::string, Subcommand>>& table);

// The full command line, shell-quoted where needed.
std::string command_line(int argc, const char* const* argv);

// A seed given as text: digits only, at most 2^64 - 1 (UsageError naming `option` otherwise).
std::uint64_t parse_seed(const std::string& text, const std::string& option);
// A thread count: 0 (all cores) up to max(256, 4 x the cores); UsageError naming `option` otherwise.
void check_threads(int threads, const std::string& option);

// "40x20" -> {40, 20}; "0.4x0.2" -> {0.4, 0.2}. Throws UsageError naming `option`.
std::array<double, 2> parse_pair_double(const std::string& text, const std::string& option);
std::array<std::int64_t, 2> parse_pair_int(const std::string& text, const std::string& option);

// The options the command line or the --config file gave (not defaulted), by long name.
std::set<std::string> given_options(const po::variables_map& vm);

// Every option in vm as text (defaulted ones too), for the record in /parameters.
std::vector<std::pair<std::string, std::string>> resolved_options(const po::variables_map& vm);

}  // namespace frac::cli
