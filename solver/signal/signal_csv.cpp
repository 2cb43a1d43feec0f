#include "solver/signal/signal_csv.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "core/errors.h"

namespace crashlink::signal {

namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

double parse_number(std::string_view field, const std::string& path, int line, const char* key) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v)) {
    throw InputError(path, line, key,
                     fmt::format("'{}' is not a finite number; write plain decimal numbers "
                                 "(e.g. 0.0125 or 1.25e-2)",
                                 field));
  }
  return v;
}

}  // namespace

CsvSignal read_signal_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw InputError(path, 0, "file", "cannot open the file; check the path and permissions");
  }
  CsvSignal s;
  std::string text;
  int line = 0;
  bool header_seen = false;
  while (std::getline(in, text)) {
    ++line;
    std::string_view v = text;
    if (line == 1 && v.starts_with("\xEF\xBB\xBF")) v.remove_prefix(3);  // UTF-8 BOM
    v = trim(v);
    if (v.empty() || v.front() == '#') continue;
    const auto comma = v.find(',');
    if (!header_seen) {
      const bool ok = comma != std::string_view::npos && trim(v.substr(0, comma)) == "time_s" &&
                      trim(v.substr(comma + 1)) == "accel_g";
      if (!ok) {
        throw InputError(path, line, "header",
                         fmt::format("found '{}'; the first line must be the header "
                                     "'time_s,accel_g' (time in s, acceleration in g)",
                                     v));
      }
      header_seen = true;
      continue;
    }
    if (comma == std::string_view::npos || v.find(',', comma + 1) != std::string_view::npos) {
      throw InputError(
          path, line, "row",
          fmt::format("'{}' does not have 2 comma-separated fields (time_s,accel_g)", v));
    }
    const double t = parse_number(v.substr(0, comma), path, line, "time_s");
    const double a = parse_number(v.substr(comma + 1), path, line, "accel_g");
    if (!s.time_s.empty() && !(t > s.time_s.back())) {
      throw InputError(path, line, "time_s",
                       fmt::format("time {} s does not increase (previous sample: {} s); sort the "
                                   "samples and drop duplicate instants",
                                   t, s.time_s.back()));
    }
    s.time_s.push_back(t);
    s.accel_g.push_back(a);
  }
  if (!header_seen) {
    throw InputError(path, line, "header",
                     "the file is empty; it must start with the header 'time_s,accel_g'");
  }
  if (s.time_s.size() < 2) {
    throw InputError(
        path, line, "rows",
        fmt::format("{} sample(s); HIC needs at least 2 (time_s,accel_g rows)", s.time_s.size()));
  }
  return s;
}

}  // namespace crashlink::signal
