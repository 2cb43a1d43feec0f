#include "solver/deck_writer/keyword_block.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string_view>

#include "core/errors.h"
#include "solver/deck_writer/number_field.h"

namespace crashlink::deck_writer {

namespace {

constexpr int kLongWidth = 20;

/// Text fields keep their standard width in long format only if they fit 20 (a heading).
bool fits_long(const Value& v) {
  return v.kind != Value::Kind::Text || static_cast<int>(v.t.size()) <= kLongWidth;
}

/// A name the deck can hold: not read as a comment ('$') or keyword ('*') line, printable, and
/// (in a field of a card) without the comma that would make the card free format.
void check_text(const std::string& keyword, std::string_view what, const std::string& t,
                bool in_field) {
  const bool lead = !t.empty() && (t.front() == '$' || t.front() == '*');
  const bool comma = in_field && t.find(',') != std::string::npos;
  bool printable = true;
  for (unsigned char c : t) printable = printable && c >= 32 && c != 127;
  if (lead || comma || !printable)
    throw ModelError(
        fmt::format("export: '{}' ({} under {}) {}; a deck would read it otherwise; fix: rename it",
                    t, what, keyword,
                    lead    ? "starts with '$' or '*' (a comment or a keyword line)"
                    : comma ? "holds a ',' (the card would be read as free format)"
                            : "holds a control character"));
}

}  // namespace

void KeywordBlock::card(deck::Layout layout, std::initializer_list<Value> values) {
  card(layout, std::vector<Value>(values));
}

void KeywordBlock::card(deck::Layout layout, std::vector<Value> values) {
  if (values.size() > layout.size())
    throw ModelError(fmt::format("internal: {} values for a card of {} fields under {}",
                                 values.size(), layout.size(), keyword_));
  for (std::size_t i = 0; i < values.size(); ++i)
    if (values[i].kind == Value::Kind::Text)
      check_text(keyword_, layout[i].name, values[i].t, true);
  cards_.push_back({layout, std::move(values), {}});
}

void KeywordBlock::line(std::string text) {
  check_text(keyword_, "title", text, false);
  cards_.push_back({{}, {}, std::move(text)});
}

void KeywordBlock::write(std::ostream& out, Rounding& rounding) const {
  // Standard columns if every value fits them exactly; long format if that makes more of them
  // exact and every text still fits.
  bool standard_exact = true, long_ok = true;
  for (const auto& c : cards_)
    for (std::size_t i = 0; i < c.values.size(); ++i) {
      const Value& v = c.values[i];
      const int w = c.layout[i].width;
      if (v.kind == Value::Kind::Real) standard_exact = standard_exact && format_real(v.r, w).exact;
      if (v.kind == Value::Kind::Int)
        standard_exact = standard_exact && !format_integer(v.i, w).empty();
      if (v.kind == Value::Kind::Text && static_cast<int>(v.t.size()) > w)
        throw ModelError(
            fmt::format("'{}' is longer than the {} characters of {} field {}; fix: "
                        "a shorter name",
                        v.t, w, keyword_, c.layout[i].name));
      long_ok = long_ok && fits_long(v);
    }
  const bool long_format = !standard_exact && long_ok;
  out << keyword_ << (long_format ? " +" : "") << '\n';
  for (const auto& c : cards_) {
    if (c.layout.empty()) {
      out << c.line << '\n';
      continue;
    }
    std::string text;
    for (std::size_t i = 0; i < c.values.size(); ++i) {
      const Value& v = c.values[i];
      const int w = long_format ? kLongWidth : c.layout[i].width;
      std::string f;
      switch (v.kind) {
        case Value::Kind::Blank:
          break;
        case Value::Kind::Int:
          f = format_integer(v.i, w);
          if (f.empty())
            throw ModelError(
                fmt::format("{} does not fit the {} columns of {} field {}; fix: "
                            "smaller ids",
                            v.i, w, keyword_, c.layout[i].name));
          break;
        case Value::Kind::Real: {
          // One column of space before the number when it fits exactly without it.
          NumberText n = format_real(v.r, w - 1);
          if (!n.exact) n = format_real(v.r, w);
          f = n.text;
          if (!n.exact) {
            const double back = std::strtod(f.c_str(), nullptr);
            const double rel = std::abs(back - v.r) / std::abs(v.r);
            ++rounding.rounded;
            if (rel > rounding.max_relative) {
              rounding.max_relative = rel;
              rounding.worst =
                  fmt::format("{} {} = {:.17g} written {}", keyword_, c.layout[i].name, v.r, f);
            }
          }
          break;
        }
        case Value::Kind::Text:
          f = v.t;
          break;
      }
      // Numbers right-aligned, texts left-aligned in their columns.
      text +=
          v.kind == Value::Kind::Text ? fmt::format("{:<{}}", f, w) : fmt::format("{:>{}}", f, w);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << '\n';
  }
}

}  // namespace crashlink::deck_writer
