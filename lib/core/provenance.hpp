#pragma once
// Provenance: who made a file, how, from what. Every output carries the history of its inputs
// plus one new entry for the tool that wrote it (newest first): the lineage of every number.
#include <string>
#include <utility>
#include <vector>

namespace frac {

struct ProvenanceEntry {
  std::string time;          // UTC, ISO 8601, when the tool started
  std::string tool;          // "mesh-gen"
  std::string version;       // toolkit version
  std::string command_line;  // full, shell-quoted
  std::string file_uuid;     // uuid of the file this tool wrote
  std::string seed;          // seed used, "" when the tool uses no randomness
};

// One part of a run continued from checkpoints: when and how it started, and from which step.
struct RunSegment {
  std::string started;  // UTC, ISO 8601
  std::string command_line;
  long long first_step = 0;
};

// Everything a tool records about one run of itself.
struct ToolRun {
  std::string tool;
  std::string command_line;
  std::string started = "";                                     // filled by start_run
  std::string seed;                                             // "" when unused
  std::vector<std::pair<std::string, std::string>> parameters;  // resolved options
  std::vector<std::string> input_uuids;                         // uuids of the files read
  std::vector<ProvenanceEntry> input_history;                   // their histories, concatenated
  std::vector<RunSegment> segments;  // a run resumed from checkpoints: its parts, the first from step 0; else empty
};

ToolRun start_run(const std::string& tool, const std::string& command_line);

// The provenance of an output without a /provenance group (PNG, SVG, CSV, XDMF; docs/SCHEMA.md), one
// line: "tool=T version=V time=UTC [seed=S] [inputs=UUID,...] command=COMMAND LINE". Control
// characters and backslashes of the command line are written as C escapes (\n, \\, \x01).
std::string provenance_line(const ToolRun& run);

std::string utc_now_iso8601();
// Random (version 4) UUID from the system's entropy; file identities, not simulation randomness.
std::string make_uuid();

}  // namespace frac
