#include "io/header.hpp"

#include <cstdlib>

#include "core/error.hpp"
#include "core/version.hpp"

namespace frac::io {

void write_header(Group& root, std::string_view kind, const ToolRun& run, const std::string& file_uuid) {
  root.set_attr("kind", kind);
  root.set_attr("format_version", std::vector<std::int64_t>{kFormatMajor, kFormatMinor});

  // H5MD 1.1 metadata.
  Group h5md = root.create_group("h5md");
  h5md.set_attr("version", std::vector<std::int64_t>{1, 1});
  Group author = h5md.create_group("author");
  const char* user = std::getenv("USER");
  author.set_attr("name", user && *user ? user : "unknown");
  Group creator = h5md.create_group("creator");
  creator.set_attr("name", run.tool);
  creator.set_attr("version", kVersion);
  Group units = h5md.create_group("modules/units");
  units.set_attr("version", std::vector<std::int64_t>{1, 0});
  units.set_attr("system", "SI");
  Group ours = h5md.create_group("modules/fracture");
  ours.set_attr("version", std::vector<std::int64_t>{kFormatMajor, kFormatMinor});
  ours.set_attr("kind", kind);
  ours.set_attr("schema", "docs/SCHEMA.md of the fracture toolkit");

  // Resolved options of the writing tool, as text attributes.
  Group params = root.create_group("parameters/" + run.tool);
  for (const auto& [key, value] : run.parameters) params.set_attr(key, value);
  if (!run.seed.empty()) params.set_attr("seed", run.seed);

  // Provenance: the new entry first, then the inputs' histories.
  std::vector<ProvenanceEntry> history;
  history.push_back({run.started, run.tool, kVersion, run.command_line, file_uuid, run.seed});
  history.insert(history.end(), run.input_history.begin(), run.input_history.end());
  Group prov = root.create_group("provenance");
  prov.set_attr("file_uuid", file_uuid);
  std::vector<std::string> time, tool, version, command, uuid, seed;
  for (const auto& e : history) {
    time.push_back(e.time);
    tool.push_back(e.tool);
    version.push_back(e.version);
    command.push_back(e.command_line);
    uuid.push_back(e.file_uuid);
    seed.push_back(e.seed);
  }
  prov.write_strings("time", time);
  prov.write_strings("tool", tool);
  prov.write_strings("version", version);
  prov.write_strings("command_line", command);
  prov.write_strings("file_uuid", uuid);
  prov.write_strings("seed", seed);
  prov.write_strings("inputs", run.input_uuids);
  if (run.segments.empty()) return;
  Group seg = prov.create_group("segments");
  std::vector<std::string> started, command_line;
  std::vector<std::int64_t> first_step;
  for (const RunSegment& s : run.segments) {
    started.push_back(s.started);
    command_line.push_back(s.command_line);
    first_step.push_back(s.first_step);
  }
  seg.write_strings("started", started);
  seg.write_strings("command_line", command_line);
  seg.write("first_step", std::span<const std::int64_t>(first_step), {first_step.size()});
}

std::vector<RunSegment> read_segments(const Group& root) {
  std::vector<RunSegment> out;
  if (!root.has("provenance/segments")) {
    const FileProvenance prov = read_provenance(root);
    if (!prov.history.empty()) out.push_back({prov.history.front().time, prov.history.front().command_line, 0});
    return out;
  }
  const Group seg = root.group("provenance/segments");
  const auto started = seg.read_strings("started");
  const auto command_line = seg.read_strings("command_line");
  const auto first_step = seg.read<std::int64_t>("first_step", nullptr, 1);
  if (command_line.size() != started.size() || first_step.size() != started.size())
    throw InputError(seg.where() + ": its datasets differ in length");
  for (std::size_t k = 0; k < started.size(); ++k) out.push_back({started[k], command_line[k], first_step[k]});
  return out;
}

std::string check_header(const Group& root, std::initializer_list<std::string_view> kinds) {
  if (!root.has_attr("kind") || !root.has_attr("format_version"))
    throw InputError(root.file() + ": not a file of this toolkit (no 'kind' or 'format_version' attribute at /)");
  const std::string kind = root.attr_string("kind");
  const auto version = root.attr_ints("format_version");
  if (version.size() != 2)
    throw InputError(root.file() + ": attribute /format_version must hold two integers (major, minor)");
  if (version[0] != kFormatMajor)
    throw InputError(root.file() + ": format version " + std::to_string(version[0]) + "." + std::to_string(version[1]) +
                     " is not supported (this build reads " + std::to_string(kFormatMajor) + ".x)");
  for (auto k : kinds)
    if (kind == k) return kind;
  std::string expected;
  for (auto k : kinds) expected += (expected.empty() ? "" : " or ") + std::string(k);
  throw InputError(root.file() + ": holds a file of kind '" + kind + "', expected " + expected);
}

FileProvenance read_provenance(const Group& root) {
  FileProvenance out;
  if (!root.has("provenance")) return out;
  const Group prov = root.group("provenance");
  if (prov.has_attr("file_uuid")) out.file_uuid = prov.attr_string("file_uuid");
  const auto time = prov.read_strings("time");
  const auto tool = prov.read_strings("tool");
  const auto version = prov.read_strings("version");
  const auto command = prov.read_strings("command_line");
  const auto uuid = prov.read_strings("file_uuid");
  const auto seed = prov.read_strings("seed");
  const std::size_t n = time.size();
  if (tool.size() != n || version.size() != n || command.size() != n || uuid.size() != n || seed.size() != n)
    throw InputError(prov.where() + ": the history datasets differ in length");
  for (std::size_t k = 0; k < n; ++k)
    out.history.push_back({time[k], tool[k], version[k], command[k], uuid[k], seed[k]});
  return out;
}

void add_input(ToolRun& run, const Group& input_root) {
  auto prov = read_provenance(input_root);
  run.input_uuids.push_back(prov.file_uuid);
  run.input_history.insert(run.input_history.end(), prov.history.begin(), prov.history.end());
}

}  // namespace frac::io
