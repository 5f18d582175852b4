#include "core/provenance.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>

#include "core/version.hpp"

namespace frac {

ToolRun start_run(const std::string& tool, const std::string& command_line) {
  ToolRun run;
  run.tool = tool;
  run.command_line = command_line;
  run.started = utc_now_iso8601();
  return run;
}

std::string provenance_line(const ToolRun& run) {
  std::string line = "tool=" + run.tool + " version=" + kVersion + " time=" + run.started;
  if (!run.seed.empty()) line += " seed=" + run.seed;
  for (std::size_t k = 0; k < run.input_uuids.size(); ++k) line += (k ? "," : " inputs=") + run.input_uuids[k];
  line += " command=";
  for (const char c : run.command_line) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\')
      line += "\\\\";
    else if (c == '\n')
      line += "\\n";
    else if (c == '\t')
      line += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      line += hex;
    } else
      line += c;
  }
  return line;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string make_uuid() {
  std::random_device rd;
  unsigned char b[16];
  for (auto& x : b) x = static_cast<unsigned char>(rd() & 0xff);
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x40);
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);
  char out[40];
  std::snprintf(out, sizeof out, "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x", b[0], b[1],
                b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14], b[15]);
  return out;
}

}  // namespace frac
