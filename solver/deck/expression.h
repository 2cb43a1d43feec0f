#pragma once
// The arithmetic of *PARAMETER_EXPRESSION: numbers, parameter names (with or without '&'),
// + - * / and ** (power), parentheses, unary minus and the functions sin cos tan asin acos atan
// atan2 sqrt abs exp log log10 min max pow (angles in radians, as LS-DYNA's).
#include <string>
#include <string_view>

namespace crashlink::deck {

class Parameters;

/// The value of `text`; throws ExpressionError (what and where in the text) on a mistake.
double evaluate_expression(std::string_view text, const Parameters& params);

struct ExpressionError {
  std::string what;  ///< e.g. "unknown name 'lenght' at character 5"
};

}  // namespace crashlink::deck
