#pragma once
// One data card of a keyword deck and its fields: fixed columns (each keyword's widths, 8/10/16/
// 20), long format (every field 20 wide: *KEYWORD LONG=Y or a `+` after the keyword) and free
// format (fields between commas). A Field is a view into the line: no allocation per card. Every
// field knows its file, line and columns, so any refusal reads
// "file:line: *KEYWORD field NAME (columns a-b) = value: what; fix".
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace crashlink::deck {

class Parameters;

enum class CardFormat : std::uint8_t { Fixed, Long, Free };

/// Where a card came from: an index into DeckFiles, a 1-based line, how it was written.
struct CardRef {
  std::uint32_t file = 0;
  std::int32_t line = 0;
  CardFormat format = CardFormat::Fixed;
};

/// One field of a card layout: its name in the LS-DYNA manual and its width in standard format.
struct FieldSpec {
  std::string_view name;
  int width;
};
using Layout = std::span<const FieldSpec>;

/// The files of a deck (index = CardRef::file), for messages.
class DeckFiles {
 public:
  std::uint32_t add(std::string path);
  const std::string& name(std::uint32_t i) const { return names_[i]; }
  std::size_t count() const { return names_.size(); }

 private:
  std::vector<std::string> names_;
};

class Card;

/// A field of a card, as written (trimmed), with its columns (1-based, inclusive).
class Field {
 public:
  Field(const Card& card, std::string_view name, std::string_view raw, int first, int last)
      : card_(&card), name_(name), raw_(raw), first_(first), last_(last) {}

  std::string_view raw() const { return raw_; }
  bool blank() const { return raw_.empty(); }
  /// The number written or referenced (&name, -&name); `fallback` if blank.
  double real(double fallback) const;
  /// The same, required to be an integer.
  std::int64_t integer(std::int64_t fallback) const;
  /// The text written (a C parameter's value for &name).
  std::string text() const;
  /// Throws InputError "file:line: *KEYWORD field NAME (columns a-b) = value: what".
  [[noreturn]] void fail(std::string_view what) const;
  /// The key part of such a message: "*KEYWORD field NAME (columns a-b) = value".
  std::string describe() const;

 private:
  const Card* card_;
  std::string_view name_;
  std::string_view raw_;
  int first_, last_;
};

/// A data card: a view of one line, valid until the reader reads the next line.
class Card {
 public:
  Card(std::string_view text, CardRef ref, std::string_view keyword, const DeckFiles& files,
       const Parameters& params)
      : text_(text), ref_(ref), keyword_(keyword), files_(&files), params_(&params) {}

  /// Field i of `layout` (blank if the card stops before it).
  Field field(Layout layout, std::size_t i) const;
  /// The whole line, right-trimmed (titles, file names).
  std::string_view whole() const;
  const CardRef& ref() const { return ref_; }
  std::string_view keyword() const { return keyword_; }
  const std::string& file() const { return files_->name(ref_.file); }
  const Parameters& parameters() const { return *params_; }
  /// Throws InputError "file:line: *KEYWORD: what" (not about one field).
  [[noreturn]] void fail(std::string_view what) const;

 private:
  std::string_view text_;
  CardRef ref_;
  std::string_view keyword_;
  const DeckFiles* files_;
  const Parameters* params_;
};

/// Text without leading and trailing blanks (spaces, tabs, CR).
std::string_view trim(std::string_view s);

}  // namespace crashlink::deck
