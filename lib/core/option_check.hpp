#pragma once
// Range checks of numeric options and scene values: UsageError naming the option (or key) and the value,
// e.g. "--significance: must lie in (0, 1), got 2".
#include <initializer_list>
#include <string>
#include <string_view>

namespace frac {

// An interval of allowed values, each end included unless open; never holds a NaN or an infinity.
struct Interval {
  double lo, hi;
  bool lo_open = false, hi_open = false;
  bool contains(double x) const;
  std::string text() const;                                                            // "(0, 1)", "[0, 1e+06]"
  static Interval closed(double lo, double hi) { return {lo, hi, false, false}; }      // [lo, hi]
  static Interval open(double lo, double hi) { return {lo, hi, true, true}; }          // (lo, hi)
  static Interval open_closed(double lo, double hi) { return {lo, hi, true, false}; }  // (lo, hi]
};

// UsageError "`option`: must lie in (0, 1), got 2" unless `x` is finite and in `range`.
void check_in(double x, const std::string& option, const Interval& range);

// UsageError "`option`: expected hdf5 or text, got 'csv'" unless `value` is one of `choices`.
void check_one_of(const std::string& value, std::initializer_list<std::string_view> choices, const std::string& option);

// A number as messages write it (6 significant digits).
std::string format_value(double x);

}  // namespace frac
