#pragma once
// One keyword and its cards, written in the keyword's standard columns when every value fits
// them exactly, else in long format (the keyword with a '+' suffix: every field 20 wide), which
// the reader (solver/deck) and LS-DYNA both take per keyword. Titles and headings stay in
// standard columns.
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <string>
#include <vector>

#include "solver/deck/card.h"

namespace crashlink::deck_writer {

/// One field's value: blank, an integer, a real or a text.
struct Value {
  enum class Kind : std::uint8_t { Blank, Int, Real, Text } kind = Kind::Blank;
  long long i = 0;
  double r = 0.0;
  std::string t;
  Value() = default;
  Value(int v) : kind(Kind::Int), i(v) {}
  Value(long v) : kind(Kind::Int), i(v) {}
  Value(long long v) : kind(Kind::Int), i(v) {}
  Value(double v) : kind(Kind::Real), r(v) {}
  Value(const char* v) : kind(Kind::Text), t(v) {}
  Value(std::string v) : kind(Kind::Text), t(std::move(v)) {}
};

/// What writing values cost in precision, summed over a deck.
struct Rounding {
  std::size_t rounded = 0;    ///< reals written with fewer digits than reading back needs
  double max_relative = 0.0;  ///< the largest |written - value| / |value|
  std::string worst;          ///< "*KEYWORD FIELD = value" of the largest
};

class KeywordBlock {
 public:
  explicit KeywordBlock(std::string keyword) : keyword_(std::move(keyword)) {}

  /// A card of `layout`'s fields in order (fewer values: the rest blank).
  void card(deck::Layout layout, std::initializer_list<Value> values);
  void card(deck::Layout layout, std::vector<Value> values);
  /// A whole-line card: a title, a file name.
  void line(std::string text);

  /// Writes the keyword line and its cards to `out`; adds the rounding to `rounding`.
  void write(std::ostream& out, Rounding& rounding) const;

 private:
  struct Card {
    deck::Layout layout;
    std::vector<Value> values;
    std::string line;  ///< a whole-line card if layout is empty
  };
  std::string keyword_;
  std::vector<Card> cards_;
};

}  // namespace crashlink::deck_writer
