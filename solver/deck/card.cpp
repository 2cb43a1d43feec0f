#include "solver/deck/card.h"

#include <charconv>
#include <cmath>

#include "core/errors.h"
#include "solver/deck/parameters.h"

namespace crashlink::deck {

std::uint32_t DeckFiles::add(std::string path) {
  names_.push_back(std::move(path));
  return static_cast<std::uint32_t>(names_.size() - 1);
}

std::string_view trim(std::string_view s) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

namespace {

/// A number as written: from_chars plus a leading '+' and Fortran's 'd' exponent.
bool parse_number(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  if (ec == std::errc() && end == s.data() + s.size()) return std::isfinite(out);
  const auto d = s.find_first_of("dD");
  if (d == std::string_view::npos || d > 64) return false;
  char buf[80];
  if (s.size() >= sizeof buf) return false;
  s.copy(buf, s.size());
  buf[d] = 'e';
  auto [end2, ec2] = std::from_chars(buf, buf + s.size(), out);
  return ec2 == std::errc() && end2 == buf + s.size() && std::isfinite(out);
}

}  // namespace

double Field::real(double fallback) const {
  if (raw_.empty()) return fallback;
  double v = 0.0;
  if (parse_number(raw_, v)) return v;
  std::string_view name = raw_;
  double sign = 1.0;
  if (name.front() == '-') {
    sign = -1.0;
    name.remove_prefix(1);
  }
  if (!name.empty() && name.front() == '&') {
    name.remove_prefix(1);
    const ParameterValue* p = card_->parameters().find(name);
    if (!p)
      fail(
          fmt::format("parameter '{}' is not defined; fix: define it in a *PARAMETER (R {} 1.0) or "
                      "*PARAMETER_EXPRESSION before this card",
                      name, name));
    if (p->type == 'C')
      fail(
          fmt::format("parameter '{}' is of type C (text '{}'), this field needs a number; fix: "
                      "define it as R or I",
                      name, p->text));
    return sign * p->number;
  }
  fail(
      "not a number; fix: write a number (e.g. 2.1e5), &name of a *PARAMETER, or leave it blank "
      "for the default");
}

std::int64_t Field::integer(std::int64_t fallback) const {
  if (raw_.empty()) return fallback;
  std::int64_t i = 0;
  std::string_view s = raw_;
  if (s.front() == '+') s.remove_prefix(1);
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), i);
  if (ec == std::errc() && end == s.data() + s.size()) return i;
  const double v = real(0.0);
  if (v != std::round(v) || std::abs(v) > 9.0e15)
    fail("not an integer; fix: write a whole number (an id, a count, a flag)");
  return static_cast<std::int64_t>(v);
}

std::string Field::text() const {
  if (!raw_.empty() && raw_.front() == '&') {
    if (const ParameterValue* p = card_->parameters().find(raw_.substr(1))) return p->text;
  }
  return std::string(raw_);
}

std::string Field::describe() const {
  return fmt::format("{} field {} (columns {}-{}) = {}", card_->keyword(), name_, first_, last_,
                     raw_.empty() ? std::string_view("(blank)") : raw_);
}

void Field::fail(std::string_view what) const {
  throw InputError(card_->file(), card_->ref().line, describe(), std::string(what));
}

void Card::fail(std::string_view what) const {
  throw InputError(file(), ref_.line, std::string(keyword_), std::string(what));
}

std::string_view Card::whole() const {
  std::string_view s = text_;
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

Field Card::field(Layout layout, std::size_t i) const {
  const std::string_view name = i < layout.size() ? layout[i].name : std::string_view("?");
  if (ref_.format == CardFormat::Free) {
    std::size_t start = 0;
    for (std::size_t k = 0; k < i; ++k) {
      const auto comma = text_.find(',', start);
      if (comma == std::string_view::npos) {
        const int col = static_cast<int>(text_.size()) + 1;
        return Field(*this, name, {}, col, col);
      }
      start = comma + 1;
    }
    auto end = text_.find(',', start);
    if (end == std::string_view::npos) end = text_.size();
    return Field(*this, name, trim(text_.substr(start, end - start)), static_cast<int>(start) + 1,
                 static_cast<int>(end));
  }
  std::size_t start = 0;
  int width = 0;
  for (std::size_t k = 0; k <= i && k < layout.size(); ++k) {
    width = ref_.format == CardFormat::Long ? 20 : layout[k].width;
    if (k < i) start += static_cast<std::size_t>(width);
  }
  const int first = static_cast<int>(start) + 1;
  const int last = static_cast<int>(start) + width;
  if (start >= text_.size()) return Field(*this, name, {}, first, last);
  return Field(*this, name, trim(text_.substr(start, static_cast<std::size_t>(width))), first,
               last);
}

}  // namespace crashlink::deck
