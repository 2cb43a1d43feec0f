#include "solver/deck/parameters.h"

#include <cctype>

namespace crashlink::deck {

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

const ParameterValue* Parameters::find(std::string_view name) const {
  const auto it = values_.find(upper(name));
  return it == values_.end() ? nullptr : &it->second;
}

const ParameterValue* Parameters::define(std::string_view name, ParameterValue v) {
  const auto [it, inserted] = values_.emplace(upper(name), std::move(v));
  return inserted ? nullptr : &it->second;
}

}  // namespace crashlink::deck
