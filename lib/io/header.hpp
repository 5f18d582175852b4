#pragma once
// What every file of the toolkit carries besides its data (docs/SCHEMA.md): root attributes (kind,
// format version), H5MD metadata (/h5md), the resolved options of the tool that wrote it
// (/parameters/<tool>) and the provenance history (/provenance), newest first.
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "core/provenance.hpp"
#include "io/hdf5.hpp"

namespace frac::io {

// Writes root attributes, /h5md, /parameters/<tool> and /provenance for a new file of `kind`.
void write_header(Group& root, std::string_view kind, const ToolRun& run, const std::string& file_uuid);

// Refuses (InputError naming the file) a file that is not ours, of an unknown major format version,
// or of a kind not in `kinds`. Returns the kind.
std::string check_header(const Group& root, std::initializer_list<std::string_view> kinds);

struct FileProvenance {
  std::string file_uuid;
  std::vector<ProvenanceEntry> history;  // newest first
};
FileProvenance read_provenance(const Group& root);

// The segments of the run that wrote `root` (/provenance/segments; a run never resumed: one, its own entry).
std::vector<RunSegment> read_segments(const Group& root);

// Records an input file in a run: its uuid and its history (so the output carries the lineage).
void add_input(ToolRun& run, const Group& input_root);

}  // namespace frac::io
