#include "solver/deck/expression.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <vector>

#include "solver/deck/parameters.h"

namespace crashlink::deck {

namespace {

/// Recursive descent: expr = term {(+|-) term}; term = unary {(*|/) unary};
/// unary = (-|+) unary | power; power = primary [** unary]; primary = number | name | name(args)
/// | (expr).
class Parser {
 public:
  Parser(std::string_view s, const Parameters& p) : s_(s), params_(p) {}

  double parse() {
    const double v = expr();
    skip();
    if (i_ < s_.size()) error(fmt::format("unexpected '{}'", s_[i_]));
    // an overflow (10**400) or a power of a negative base (pow(-1, 0.5)) would carry inf or NaN
    // into a density, a modulus or a coordinate
    if (!std::isfinite(v)) error(fmt::format("the value {} is not a finite number", v));
    return v;
  }

 private:
  [[noreturn]] void error(const std::string& what) const {
    throw ExpressionError{fmt::format("{} at character {} of '{}'", what, i_ + 1, s_)};
  }
  void skip() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }
  bool eat(char c) {
    skip();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }

  double expr() {
    double v = term();
    for (;;) {
      if (eat('+'))
        v += term();
      else if (eat('-'))
        v -= term();
      else
        return v;
    }
  }
  double term() {
    double v = unary();
    for (;;) {
      skip();
      if (i_ + 1 < s_.size() && s_[i_] == '*' && s_[i_ + 1] == '*') return v;  // power: below
      if (eat('*')) {
        v *= unary();
      } else if (eat('/')) {
        const double d = unary();
        if (d == 0.0) error("division by zero");
        v /= d;
      } else {
        return v;
      }
    }
  }
  double unary() {
    if (eat('-')) return -unary();
    if (eat('+')) return unary();
    return power();
  }
  double power() {
    const double base = primary();
    skip();
    if (i_ + 1 < s_.size() && s_[i_] == '*' && s_[i_ + 1] == '*') {
      i_ += 2;
      return std::pow(base, unary());
    }
    return base;
  }
  double primary() {
    skip();
    if (i_ >= s_.size()) error("the expression ends too early");
    const char c = s_[i_];
    if (c == '(') {
      ++i_;
      // nesting cap: the recursion must not exhaust the stack on a hostile card
      if (++depth_ > kMaxDepth) error(fmt::format("parentheses nested deeper than {}", kMaxDepth));
      const double v = expr();
      --depth_;
      if (!eat(')')) error("missing ')'");
      return v;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (c == '&' || std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    error(fmt::format("unexpected '{}'", c));
  }
  double number() {
    double v = 0.0;
    auto [end, ec] = std::from_chars(s_.data() + i_, s_.data() + s_.size(), v);
    if (ec != std::errc()) error("malformed number");
    i_ = static_cast<std::size_t>(end - s_.data());
    return v;
  }
  double name() {
    if (s_[i_] == '&') ++i_;
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_'))
      ++i_;
    const std::string_view n = s_.substr(start, i_ - start);
    if (eat('(')) return call(n);
    const ParameterValue* p = params_.find(n);
    if (!p) {
      i_ = start;
      error(fmt::format("unknown name '{}' (define it in a *PARAMETER before this expression)", n));
    }
    if (p->type == 'C') {
      i_ = start;
      error(fmt::format("parameter '{}' is text (type C)", n));
    }
    return p->number;
  }
  double call(std::string_view fname) {
    std::vector<double> args;
    if (!eat(')')) {
      do {
        args.push_back(expr());
      } while (eat(','));
      if (!eat(')')) error("missing ')' after the arguments");
    }
    const std::string f = upper(fname);
    auto want = [&](std::size_t n) {
      if (args.size() != n)
        error(fmt::format("{} takes {} argument(s), got {}", fname, n, args.size()));
    };
    struct Unary {
      const char* name;
      double (*f)(double);
    };
    static const Unary unaries[] = {{"SIN", [](double x) { return std::sin(x); }},
                                    {"COS", [](double x) { return std::cos(x); }},
                                    {"TAN", [](double x) { return std::tan(x); }},
                                    {"ASIN", [](double x) { return std::asin(x); }},
                                    {"ACOS", [](double x) { return std::acos(x); }},
                                    {"ATAN", [](double x) { return std::atan(x); }},
                                    {"SQRT", [](double x) { return std::sqrt(x); }},
                                    {"ABS", [](double x) { return std::abs(x); }},
                                    {"EXP", [](double x) { return std::exp(x); }},
                                    {"LOG", [](double x) { return std::log(x); }},
                                    {"LOG10", [](double x) { return std::log10(x); }}};
    for (const auto& u : unaries)
      if (f == u.name) {
        want(1);
        const double v = u.f(args[0]);
        if (!std::isfinite(v)) error(fmt::format("{}({}) is not a finite number", fname, args[0]));
        return v;
      }
    if (f == "ATAN2" || f == "POW") {
      want(2);
      return f == "POW" ? std::pow(args[0], args[1]) : std::atan2(args[0], args[1]);
    }
    if (f == "MIN" || f == "MAX") {
      if (args.empty()) error(fmt::format("{} needs at least one argument", fname));
      double v = args[0];
      for (double a : args) v = f == "MIN" ? std::min(v, a) : std::max(v, a);
      return v;
    }
    error(
        fmt::format("unknown function '{}' (known: sin cos tan asin acos atan atan2 sqrt abs "
                    "exp log log10 min max pow)",
                    fname));
  }

  static constexpr int kMaxDepth = 64;
  std::string_view s_;
  const Parameters& params_;
  std::size_t i_ = 0;
  int depth_ = 0;
};

}  // namespace

double evaluate_expression(std::string_view text, const Parameters& params) {
  return Parser(text, params).parse();
}

}  // namespace crashlink::deck
