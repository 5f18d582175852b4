#include "core/checkpoint_options.hpp"

#include <cmath>
#include <cstdlib>

#include "core/error.hpp"

namespace frac {

void parse_checkpoint_every(const std::string& text, const std::string& option, CheckpointOptions& out) {
  const auto bad = [&] {
    return UsageError(option + " '" + text +
                      "': expected a number of steps (e.g. 10000), a wall-clock time (e.g. "
                      "600s, 15min, 2h) or 0");
  };
  const std::size_t digits = text.find_first_not_of("0123456789.");
  const std::string number = text.substr(0, digits), unit = digits == std::string::npos ? "" : text.substr(digits);
  if (number.empty() || number.find_first_not_of("0123456789.") != std::string::npos) throw bad();
  char* end = nullptr;
  const double x = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || !std::isfinite(x) || x < 0) throw bad();
  out.every_steps = 0;
  out.every_seconds = 0;
  if (unit.empty()) {
    if (number.find('.') != std::string::npos || x > 9e18) throw bad();
    out.every_steps = static_cast<std::int64_t>(x);
    return;
  }
  const double scale = unit == "s" ? 1 : unit == "min" ? 60 : unit == "h" ? 3600 : 0;
  if (scale == 0 || x * scale > 1e9) throw bad();
  out.every_seconds = x * scale;
}

std::string checkpoint_path(const CheckpointOptions& options, const std::string& output) {
  if (!options.path.empty()) return options.path;
  return output == "-" ? "" : output + ".ckpt";
}

}  // namespace frac
