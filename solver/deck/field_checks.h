#pragma once
// Checks of single fields shared by the card readers (deck_parser.cpp, interaction_cards.cpp):
// each refusal names the field ("file:line: *KEYWORD field NAME (columns a-b) = value: what").
#include <fmt/format.h>

#include <cstdint>
#include <string_view>

#include "solver/deck/card.h"

namespace crashlink::deck {

inline bool blank(const Card& c) {
  return trim(c.whole()).empty();
}

inline std::int64_t positive_id(const Field& f) {
  const std::int64_t v = f.integer(0);
  if (v <= 0) f.fail("an id must be a positive integer; fix: write one");
  return v;
}
inline double positive(const Field& f, const char* example) {
  const double v = f.real(0.0);
  if (!(v > 0.0)) f.fail(fmt::format("must be > 0; fix: write it, e.g. {}", example));
  return v;
}
/// A field crashlink does not compute: must be blank or `zero`.
inline void must_be_default(const Field& f, double zero, std::string_view what) {
  if (f.blank()) return;
  if (f.real(zero) != zero) f.fail(what);
}

/// A death time crashlink does not compute: blank, 0 or 1e20 and up (LS-DYNA's "never").
inline void must_never_die(const Field& f, std::string_view what) {
  if (f.blank()) return;
  const double t = f.real(0.0);
  if (t != 0.0 && t < 1e20) f.fail(what);
}

}  // namespace crashlink::deck
