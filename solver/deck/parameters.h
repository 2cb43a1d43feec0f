#pragma once
// *PARAMETER and *PARAMETER_EXPRESSION values (types R, I, C) and their `&name` references.
// Names are case-insensitive, as LS-DYNA's; defining a name twice is refused.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "solver/deck/card.h"

namespace crashlink::deck {

struct ParameterValue {
  char type = 'R';  ///< 'R' real, 'I' integer, 'C' character
  double number = 0.0;
  std::string text;  ///< C: the value; R/I: as written
  CardRef where;     ///< where it was defined
};

class Parameters {
 public:
  /// nullptr if `name` (without '&', any case) is not defined.
  const ParameterValue* find(std::string_view name) const;
  /// Defines `name`; returns the earlier definition instead if there is one (nothing changed).
  const ParameterValue* define(std::string_view name, ParameterValue v);
  std::size_t count() const { return values_.size(); }

 private:
  std::unordered_map<std::string, ParameterValue> values_;
};

/// Upper-case copy (keyword and parameter names).
std::string upper(std::string_view s);

}  // namespace crashlink::deck
