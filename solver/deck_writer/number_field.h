#pragma once
// A real number written into a fixed-width field of a keyword deck, as exactly as the width
// allows: the shortest text that reads back to the same double, else the most digits that fit.
#include <string>

namespace crashlink::deck_writer {

struct NumberText {
  std::string text;
  bool exact = true;  ///< reads back to the same double
};

/// The shortest text of `v` that fits `width` characters and reads back (strtod) to `v` exactly:
/// the shortest round-trip form, fixed or scientific, a leading "0." written ".", the exponent
/// without '+' and leading zeros when that makes it fit; else the most significant digits that
/// fit (exact = false). Throws ModelError if `v` is not finite.
NumberText format_real(double v, int width);

/// `v` in decimal; empty if it needs more than `width` characters.
std::string format_integer(long long v, int width);

}  // namespace crashlink::deck_writer
