#pragma once
// The observables of a run (/observables/<name>/{step,time,value}) as one table on a common time axis,
// row selection and straight-line fits between columns: the elastic moduli of the uniaxial test are
// slopes of stress and lateral strain against axial strain.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "analysis/wave_speed.hpp"  // LineFit, fit_line
#include "io/hdf5.hpp"

namespace frac::analysis {

struct ObservableTable {
  std::vector<double> time;  // s
  std::vector<std::string> names, units;
  std::vector<std::vector<double>> columns;                                    // columns[c][row]
  std::size_t column(const std::string& name, const std::string& file) const;  // InputError if absent
};

std::vector<std::string> split_names(const std::string& comma_separated);
// The scalar observables sampled at the same times as the first one (all of dem-run's are); `names`
// empty = every scalar observable. InputError naming the file and observable when one is missing or
// sampled at other times.
ObservableTable read_observables(const io::Group& root, const std::vector<std::string>& names);
// As CSV: the provenance line as a '#' comment, the header (names with their units), the rows.
void write_csv(const ObservableTable& table, std::ostream& out, const std::string& provenance);
// Rows with time > after and, if `condition` ("name>value" or "name<value") is given, satisfying it.
std::vector<std::uint8_t> select_rows(const ObservableTable& table, const std::string& condition, double after,
                                      const std::string& file);
// Least squares y = intercept + slope·x over the selected rows; InputError when fewer than 3 rows.
LineFit fit_columns(const ObservableTable& table, const std::string& y, const std::string& x,
                    const std::vector<std::uint8_t>& rows, const std::string& file);

// A resolved parameter of the run (/parameters/<tool>, the tool that wrote the run); InputError if absent.
std::string run_parameter(const io::Group& root, const std::string& name);

// Distance between the final positions of two runs of the same mesh (rms and largest, m), and their
// final times: the displacement error of a run against a reference run.
struct PositionDifference {
  double rms = 0, max = 0, time = 0, reference_time = 0;
};
PositionDifference compare_final_positions(const io::Group& run, const io::Group& reference, const std::string& file,
                                           const std::string& reference_file);

}  // namespace frac::analysis
