#include "core/errors.h"

namespace crashlink {

InputError::InputError(const std::string& file, int line, const std::string& key,
                       const std::string& what)
    : Error(fmt::format("{}:{}: {}: {}", file, line, key, what)),
      file_(file),
      line_(line),
      key_(key) {}

}  // namespace crashlink
