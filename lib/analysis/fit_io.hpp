#pragma once
// powerlaw-fit's file formats: the values to fit (a /fragments file, or a plain column of numbers) and the
// fit itself (the /fit group of an HDF5 file of kind "fit", or "key value" lines for shell scripts).
// Layout and keys: docs/powerlaw-fit.md.
#include <cmath>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "analysis/powerlaw.hpp"
#include "core/provenance.hpp"
#include "io/hdf5.hpp"

namespace frac::analysis {

// The values to fit and where they came from.
struct FitInput {
  std::vector<double> values;
  std::string source;                     // "values.txt", "-", "fragments.h5:/fragments/mass"
  std::string column;                     // "mass" or "cell_count" for a fragments file, "" for text
  std::string unit;                       // "kg", "1", or "" (unknown, text input)
  std::int64_t n_read = 0;                // values read before any filter
  std::int64_t n_excluded_min_cells = 0;  // fragments below --min-cells (reported, never silent)
  std::int64_t min_cells = 0;             // the --min-cells filter applied (0: none)
  std::int64_t fragments_min_cells = -1;  // min_cells attribute of the fragments file (-1: none)
  double total_mass = 0;                  // kg: all cells of the fragments files read (0 for text)
  std::int64_t cells = 0;                 // their number
  std::vector<std::size_t> input_sizes;   // values from each pooled input, in order (pool_into)

  // total_mass / cells: what a fragment of k cells weighs about k times (0 without fragments files, or when a
  // mass is not finite: the fit refuses those values anyway).
  double mean_cell_mass() const {
    return cells > 0 && total_mass > 0 && std::isfinite(total_mass) ? total_mass / static_cast<double>(cells) : 0.0;
  }
};

// One number a line; blank lines and '#' comments skipped. InputError naming `name`, the number of bad lines
// and the first of them, for a line that is not a single number. NaN and infinities are read as such
// (validate_values refuses them, with counts). Bounded, so that a stream that is no column of numbers
// (/dev/zero, `yes`, a binary file) is refused instead of read until time or memory runs out: InputError for
// a line over 4096 characters or with a NUL byte, after 1000 bad lines, and past `max_values` values.
inline constexpr std::size_t kMaxTextValues = std::size_t{1} << 27;
std::vector<double> read_number_column(std::istream& in, const std::string& name,
                                       std::size_t max_values = kMaxTextValues);
// A text file, or "-" for standard input.
FitInput read_text_values(const std::string& path);

// /fragments/<column> (mass or cell_count) of a file of kind "fragments"; with min_cells > 0, only fragments
// of at least that many cells (the number left out is reported).
FitInput read_fragment_values(const io::Group& root, const std::string& column, std::int64_t min_cells = 0);
// The min_cells attribute of /fragments (what fragment-count was asked to leave out of its histogram), 0 when
// absent. Checks the header (kind "fragments") and that /fragments exists.
std::int64_t fragments_min_cells(const io::Group& root);

// Does `path` ("-": standard input, peeked without consuming it) hold an HDF5 file? InputError when the file
// is missing or standard input is empty.
bool input_is_hdf5(const std::string& path);

// How powerlaw-fit reads its inputs.
struct InputOptions {
  std::string format = "auto";           // auto (HDF5 when the input starts with its signature), hdf5 or text
  std::string column = "mass";           // fragments files: mass or cell_count
  bool fragments_options_given = false;  // --column or --min-cells given: text input is refused
  std::function<std::int64_t(const io::Group&)> min_cells;  // a fragments file's --min-cells filter
};
// Reads every input (fragments files or text columns, each pooled once: DistinctInputs) into one sample,
// recording the HDF5 inputs in `run`'s provenance.
FitInput read_pooled_inputs(const std::vector<std::string>& inputs, const InputOptions& options, ToolRun& run);

// Writes the /fit group (the header is the caller's: write_header(root, "fit", ...)).
void write_fit(io::Group& root, const FitReport& report, const FitInput& input);
// Reads a /fit group back: estimators (fit, bootstrap and goodness-of-fit numbers), comparisons, histogram
// and log-binned slope. InputError when the group is missing.
FitReport read_fit(const io::Group& root);

// "key value" lines (docs/powerlaw-fit.md lists every key) after '#' lines: `provenance`
// (frac::provenance_line) first, then what alpha means.
void write_fit_text(std::ostream& out, const FitReport& report, const FitInput& input, const std::string& provenance);
// Writes `path` ("-": standard output) whole: the key value lines of write_fit_text (text) or an HDF5 file of
// kind "fit" (header and /fit) for `run`.
void write_fit_file(const std::string& path, const FitReport& report, const FitInput& input, const ToolRun& run,
                    bool text);
// powerlaw-fit's inputs, each pooled once: pooling a file twice would count its values twice. UsageError naming
// both arguments when two name one file (the same device and inode: a.h5 and ./a.h5, a link, '-' and the file
// standard input reads) or two fragments files are copies of one (the same /provenance file_uuid).
class DistinctInputs {
 public:
  explicit DistinctInputs(const std::vector<std::string>& paths);  // checks the paths
  // Input k (paths[k]), opened as `root`: checks its uuid against the inputs added before.
  void add(std::size_t k, const io::Group& root);

 private:
  std::vector<std::string> paths_;
  std::vector<std::pair<std::string, std::size_t>> uuids_;  // uuid, input
};

// Appends the values of `one` to `pooled` (the sample of several files): sources joined with " + ",
// counts, masses and cells added, its size appended to input_sizes; the unit and column must agree
// (InputError otherwise).
void pool_into(FitInput& pooled, const FitInput& one);
// The log-binned density histogram as CSV: the provenance line as a '#' comment, the header
// center,density,count,lower,upper, the bins.
void write_histogram_csv(std::ostream& out, const FitReport& report, const std::string& provenance);

}  // namespace frac::analysis
