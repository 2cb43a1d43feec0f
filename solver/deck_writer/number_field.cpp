#include "solver/deck_writer/number_field.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string_view>

#include "core/errors.h"

namespace crashlink::deck_writer {

namespace {

/// The shorter spellings of the same number: "0.5" -> ".5", "-0.5" -> "-.5", "1e+05" -> "1e5",
/// "1e-05" -> "1e-5", an integer "7850" -> "7850." (a real field's decimal point).
std::string compact(std::string s) {
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  if (s.rfind("-0.", 0) == 0) s.erase(1, 1);
  if (const auto e = s.find('e'); e != std::string::npos) {
    std::string mant = s.substr(0, e), ex = s.substr(e + 1);
    const bool neg = !ex.empty() && ex[0] == '-';
    if (!ex.empty() && (ex[0] == '+' || ex[0] == '-')) ex.erase(0, 1);
    while (ex.size() > 1 && ex[0] == '0') ex.erase(0, 1);
    s = mant + "e" + (neg ? "-" : "") + ex;
  } else if (s.find('.') == std::string::npos) {
    s += '.';
  }
  return s;
}

bool reads_back(const std::string& s, double v) {
  double r = 0.0;
  const char* b = s.data();
  const char* e = b + s.size();
  const auto [end, ec] = std::from_chars(b, e, r);
  return ec == std::errc() && end == e && r == v;
}

std::string shortest(double v, std::chars_format f) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, f);
  return std::string(buf, ec == std::errc() ? end : buf);
}

}  // namespace

NumberText format_real(double v, int width) {
  if (!std::isfinite(v))
    throw ModelError(fmt::format("a value to write is not finite ({}); fix: check the model", v));
  if (v == 0.0) return {width >= 3 ? "0.0" : "0.", true};
  std::string best;
  for (auto f :
       {std::chars_format::general, std::chars_format::fixed, std::chars_format::scientific}) {
    const std::string s = compact(shortest(v, f));
    if (reads_back(s, v) && (best.empty() || s.size() < best.size())) best = s;
  }
  if (static_cast<int>(best.size()) <= width) return {best, true};
  // The digits as an integer mantissa: "-6.938893903907228e-18" -> "-6938893903907228e-33".
  {
    const std::string sci = shortest(v, std::chars_format::scientific);
    const auto e = sci.find('e');
    std::string mant = sci.substr(0, e);
    int ex = std::atoi(sci.c_str() + e + 1);
    if (const auto dot = mant.find('.'); dot != std::string::npos) {
      ex -= static_cast<int>(mant.size() - dot - 1);
      mant.erase(dot, 1);
    }
    const std::string s = mant + "e" + std::to_string(ex);
    if (static_cast<int>(s.size()) <= width && reads_back(s, v)) return {s, true};
  }
  // Too long: the most significant digits that fit, fixed or scientific.
  for (int digits = 17; digits >= 1; --digits) {
    for (const std::string& s : {compact(fmt::format("{:.{}e}", v, digits - 1)),
                                 compact(fmt::format("{:.{}g}", v, digits))}) {
      if (static_cast<int>(s.size()) <= width) return {s, reads_back(s, v)};
    }
  }
  throw ModelError(
      fmt::format("{} does not fit a field of {} characters; fix: write the deck in "
                  "another unit system (--units)",
                  v, width));
}

std::string format_integer(long long v, int width) {
  std::string s = std::to_string(v);
  return static_cast<int>(s.size()) <= width ? s : std::string();
}

}  // namespace crashlink::deck_writer
