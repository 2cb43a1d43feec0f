#include "solver/deck/card_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/errors.h"
#include "solver/deck/expression.h"

namespace crashlink::deck {

namespace fs = std::filesystem;

struct CardReader::OpenFile {
  std::ifstream in;
  std::string buf;
  std::uint32_t index = 0;
  int line = 0;
  fs::path dir;
  bool include_block = false;  // the cards of this file's current block are file names
  bool long_format = false;    // *KEYWORD LONG=Y in this file or a file including it
};

namespace {

constexpr std::size_t kMaxIncludeDepth = 32;

constexpr FieldSpec kParameterCard[] = {{"PRMR1", 10}, {"VAL1", 10}, {"PRMR2", 10}, {"VAL2", 10},
                                        {"PRMR3", 10}, {"VAL3", 10}, {"PRMR4", 10}, {"VAL4", 10}};
constexpr FieldSpec kIncludeCard[] = {{"FILENAME", 80}};
constexpr FieldSpec kExpressionCard[] = {{"PRMR", 10}, {"EXPRESSION", 70}};

}  // namespace

CardReader::CardReader(const std::string& path, DeckFiles& files, Parameters& params)
    : files_(files), params_(params) {
  open(path, nullptr);
}

CardReader::~CardReader() = default;

void CardReader::open(const std::string& path, const CardRef* from) {
  if (stack_.size() >= kMaxIncludeDepth)
    throw InputError(files_.name(from->file), from->line, "*INCLUDE",
                     fmt::format("includes nested deeper than {} files (a file including itself?)"
                                 "; fix: include each file once",
                                 kMaxIncludeDepth));
  auto f = std::make_unique<OpenFile>();
  f->in.open(path, std::ios::binary);
  if (!f->in) {
    if (from)
      throw InputError(files_.name(from->file), from->line, "*INCLUDE",
                       fmt::format("cannot open '{}'; fix: give a path relative to the including "
                                   "file or add its folder to *INCLUDE_PATH",
                                   path));
    throw InputError(path, 0, "(file)", "cannot open the deck; fix: check the path");
  }
  f->index = files_.add(path);
  f->long_format = !stack_.empty() && stack_.back()->long_format;
  f->dir = fs::path(path).parent_path();
  stack_.push_back(std::move(f));
}

bool CardReader::read_line() {
  while (!stack_.empty()) {
    OpenFile& f = *stack_.back();
    if (std::getline(f.in, f.buf)) {
      ++f.line;
      if (!f.buf.empty() && f.buf.back() == '\r') f.buf.pop_back();
      if (!f.buf.empty() && f.buf.front() == '$') continue;
      line_ = f.buf;
      line_ref_ = CardRef{f.index, f.line, block_format_};
      return true;
    }
    stack_.pop_back();
  }
  return false;
}

Card CardReader::card() const {
  CardRef ref = line_ref_;
  if (line_.find(',') != std::string_view::npos) ref.format = CardFormat::Free;
  return Card(line_, ref, keyword_, files_, params_);
}

void CardReader::skip_block() {
  while (read_line()) {
    if (line_ref_.file != keyword_ref_.file || (!line_.empty() && line_.front() == '*')) {
      pending_ = true;
      return;
    }
  }
}

void CardReader::read_include(bool path_list, bool relative) {
  (void)relative;  // paths are resolved against the including file in both forms
  OpenFile& f = *stack_.back();
  // The card on a copy of its line: reading a continuation line below replaces the file's buffer
  // (and the end of the file closes it), which a view into it would not survive.
  const std::string first_line(line_);
  const Card probe = card();
  const Card c(first_line, probe.ref(), keyword_, files_, params_);
  std::string name(c.field(kIncludeCard, 0).text());
  if (c.ref().format == CardFormat::Free) name = std::string(trim(c.whole()));
  // A name longer than a card continues on the next line after " +", in the same file.
  const std::size_t depth = stack_.size();
  while (name.size() >= 2 && name.compare(name.size() - 2, 2, " +") == 0) {
    name.resize(name.size() - 2);
    if (!read_line() || stack_.size() != depth || stack_.back().get() != &f)
      c.field(kIncludeCard, 0)
          .fail(
              "the file name continues (\" +\") past the end of its file; fix: finish the name "
              "on the next line of the same file");
    name += std::string(trim(line_));
  }
  if (name.empty()) return;
  if (path_list) {
    fs::path p(name);
    include_paths_.push_back((p.is_relative() ? f.dir / p : p).string());
    return;
  }
  fs::path p(name);
  std::string found;
  if (p.is_absolute()) {
    found = name;
  } else {
    std::vector<fs::path> tried{f.dir / p};
    for (const auto& dir : include_paths_) tried.push_back(fs::path(dir) / p);
    for (const auto& t : tried)
      if (fs::exists(t)) {
        found = t.string();
        break;
      }
    if (found.empty()) {
      std::string where;
      for (const auto& t : tried) where += (where.empty() ? "" : ", ") + t.string();
      c.field(kIncludeCard, 0)
          .fail(fmt::format("no such file (looked for {}); fix: give the path relative to the "
                            "including file, or add its folder to *INCLUDE_PATH",
                            where));
    }
  }
  for (const auto& open_file : stack_)
    if (fs::exists(found) && files_.name(open_file->index) != found &&
        fs::equivalent(files_.name(open_file->index), found))
      c.field(kIncludeCard, 0)
          .fail(
              "includes a file that is already being read (an include cycle); fix: remove "
              "this *INCLUDE");
  const CardRef from = c.ref();
  f.include_block = true;
  open(found, &from);
}

void CardReader::read_parameters() {
  const Card c = card();
  for (std::size_t k = 0; k + 1 < 8; k += 2) {
    const Field name_field = c.field(kParameterCard, k);
    if (name_field.blank()) continue;
    const std::string_view spec = name_field.raw();
    const char type = static_cast<char>(std::toupper(static_cast<unsigned char>(spec.front())));
    const std::string_view name = trim(spec.substr(1));
    if ((type != 'R' && type != 'I' && type != 'C') || name.empty())
      name_field.fail(
          "a parameter is its type letter (R real, I integer, C text) then its name, e.g. "
          "'R tend'; fix: write it so");
    const Field value_field = c.field(kParameterCard, k + 1);
    ParameterValue v;
    v.type = type;
    v.where = c.ref();
    if (type == 'C') {
      v.text = value_field.text();
    } else {
      v.number = type == 'I' ? static_cast<double>(value_field.integer(0)) : value_field.real(0.0);
      v.text = fmt::format("{}", v.number);
    }
    if (const ParameterValue* old = params_.define(name, std::move(v)))
      name_field.fail(
          fmt::format("parameter '{}' is already defined at {}:{}; fix: give it "
                      "another name (parameters are global and case-insensitive)",
                      name, files_.name(old->where.file), old->where.line));
  }
}

void CardReader::read_parameter_expressions() {
  const Card c = card();
  std::string_view spec, expression;
  const auto comma = line_.find(',');
  if (comma != std::string_view::npos && comma < 11) {
    spec = trim(line_.substr(0, comma));
    expression = trim(line_.substr(comma + 1));
  } else {
    spec = trim(line_.substr(0, std::min<std::size_t>(10, line_.size())));
    expression = line_.size() > 10 ? trim(line_.substr(10)) : std::string_view();
  }
  const Field name_field = c.field(kExpressionCard, 0);
  if (spec.empty()) return;
  const char type = static_cast<char>(std::toupper(static_cast<unsigned char>(spec.front())));
  const std::string_view name = trim(spec.substr(1));
  if ((type != 'R' && type != 'I') || name.empty())
    name_field.fail(
        "an expression parameter is R or I then its name, e.g. 'R area'; fix: write "
        "it so");
  const Field expr_field = c.field(kExpressionCard, 1);
  if (expression.empty()) expr_field.fail("no expression; fix: write one, e.g. 2*length");
  ParameterValue v;
  v.type = type;
  v.where = c.ref();
  try {
    v.number = evaluate_expression(expression, params_);
  } catch (const ExpressionError& e) {
    expr_field.fail(e.what + "; fix: correct the expression");
  }
  if (type == 'I') v.number = std::round(v.number);
  v.text = fmt::format("{}", v.number);
  if (const ParameterValue* old = params_.define(name, std::move(v)))
    name_field.fail(
        fmt::format("parameter '{}' is already defined at {}:{}; fix: give it "
                    "another name",
                    name, files_.name(old->where.file), old->where.line));
}

bool CardReader::handle_own_keyword() {
  const std::string_view k = keyword_;
  if (k == "*KEYWORD") {
    const std::string o = upper(options_);
    if (o.find("LONG=Y") != std::string::npos) stack_.back()->long_format = true;
    if (o.find("LONG=S") != std::string::npos) stack_.back()->long_format = false;
    return true;
  }
  if (k == "*END") {
    if (!stack_.empty()) stack_.pop_back();
    return true;
  }
  if (k == "*COMMENT") {
    skip_block();
    return true;
  }
  const bool include = k == "*INCLUDE";
  const bool path = k == "*INCLUDE_PATH" || k == "*INCLUDE_PATH_RELATIVE";
  if (include || path) {
    while (read_line()) {
      if (line_ref_.file != keyword_ref_.file || (!line_.empty() && line_.front() == '*')) {
        pending_ = true;  // the next keyword, or the including file once this one ends
        return true;
      }
      if (trim(line_).empty()) continue;
      read_include(path, k == "*INCLUDE_PATH_RELATIVE");
      if (include) return true;  // the included file is read now; more names come after it
    }
    return true;
  }
  const bool param = k == "*PARAMETER";
  const bool expression = k == "*PARAMETER_EXPRESSION";
  if (param || expression) {
    while (read_line()) {
      if (line_ref_.file != keyword_ref_.file || (!line_.empty() && line_.front() == '*')) {
        pending_ = true;  // the next keyword, or the including file once this one ends
        return true;
      }
      if (trim(line_).empty()) continue;
      if (param)
        read_parameters();
      else
        read_parameter_expressions();
    }
    return true;
  }
  return false;
}

CardReader::Event CardReader::next() {
  for (;;) {
    if (!pending_ && !read_line()) return Event::End;
    pending_ = false;
    OpenFile& f = *stack_.back();
    if (line_.empty() || line_.front() != '*') {
      if (f.include_block) {  // a further file name of an *INCLUDE block
        if (trim(line_).empty()) continue;
        read_include(false, false);
        continue;
      }
      return Event::Card;
    }
    f.include_block = false;
    std::string_view rest = line_.substr(1);
    const auto end = rest.find_first_of(" \t");
    std::string_view name = rest.substr(0, end);
    options_ = end == std::string_view::npos ? std::string() : std::string(trim(rest.substr(end)));
    bool plus = false, minus = false;
    if (!name.empty() && name.back() == '+') {
      plus = true;
      name.remove_suffix(1);
    } else if (!name.empty() && name.back() == '-') {
      minus = true;
      name.remove_suffix(1);
    }
    if (options_ == "+") plus = true;
    if (options_ == "-") minus = true;
    keyword_.assign(1, '*');
    keyword_ += upper(trim(name));
    keyword_ref_ = line_ref_;
    block_format_ = plus                        ? CardFormat::Long
                    : (f.long_format && !minus) ? CardFormat::Long
                                                : CardFormat::Fixed;
    if (handle_own_keyword()) continue;
    return Event::Keyword;
  }
}

}  // namespace crashlink::deck
