#pragma once
// Streaming reader of keyword files: one line at a time, `$` comments skipped, keyword lines
// split from data cards, and the keywords that shape the input handled here so that the deck
// parser sees one flat stream: *KEYWORD (LONG=Y: for that file and the files it includes),
// *INCLUDE (relative to the including file, then
// the *INCLUDE_PATH folders), *INCLUDE_PATH(_RELATIVE), *PARAMETER (R, I, C),
// *PARAMETER_EXPRESSION, *COMMENT and *END (ends the file it is in). Memory: one line buffer per
// open file; nothing is kept per card.
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "solver/deck/card.h"
#include "solver/deck/parameters.h"

namespace crashlink::deck {

class CardReader {
 public:
  /// Opens `path` (InputError if it cannot be read).
  CardReader(const std::string& path, DeckFiles& files, Parameters& params);
  ~CardReader();

  enum class Event { Keyword, Card, End };
  /// Moves to the next keyword or data card of the deck (across includes).
  Event next();

  /// After Event::Keyword: the keyword in upper case with its '*', without options or '+'
  /// (e.g. "*ELEMENT_SOLID"), the rest of its line, where it is.
  std::string_view keyword() const { return keyword_; }
  std::string_view keyword_options() const { return options_; }
  const CardRef& keyword_ref() const { return keyword_ref_; }
  /// After Event::Card: the card (a view valid until the next call of next()).
  Card card() const;
  const DeckFiles& files() const { return files_; }
  /// Parameters defined so far.
  const Parameters& parameters() const { return params_; }

 private:
  struct OpenFile;
  bool read_line();           // next non-comment line of the innermost file, or false
  bool handle_own_keyword();  // true if keyword_ is one of ours (its cards consumed)
  void open(const std::string& path, const CardRef* from);
  void read_include(bool path_list, bool relative);
  void read_parameters();
  void read_parameter_expressions();
  void skip_block();

  DeckFiles& files_;
  Parameters& params_;
  std::vector<std::unique_ptr<OpenFile>> stack_;
  std::vector<std::string> include_paths_;
  bool pending_ = false;   // line_ holds a keyword line not returned yet
  std::string_view line_;  // current line (view into the innermost buffer)
  CardRef line_ref_;
  std::string keyword_;
  std::string options_;
  CardRef keyword_ref_;
  CardFormat block_format_ = CardFormat::Fixed;
};

}  // namespace crashlink::deck
