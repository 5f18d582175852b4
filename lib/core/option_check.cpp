#include "core/option_check.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace frac {

bool Interval::contains(double x) const {
  return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
}

std::string Interval::text() const {
  return (lo_open ? "(" : "[") + format_value(lo) + ", " + format_value(hi) + (hi_open ? ")" : "]");
}

void check_in(double x, const std::string& option, const Interval& range) {
  if (!range.contains(x)) throw UsageError(option + ": must lie in " + range.text() + ", got " + format_value(x));
}

void check_one_of(const std::string& value, std::initializer_list<std::string_view> choices,
                  const std::string& option) {
  std::string list;
  std::size_t k = 0;
  for (const std::string_view c : choices) {
    if (value == c) return;
    list += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(c);
    ++k;
  }
  throw UsageError(option + ": expected " + list + ", got '" + value + "'");
}

std::string format_value(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

}  // namespace frac
