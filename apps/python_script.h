#pragma once
// Runs one of the plotting scripts of tools/ (matplotlib, h5py) with /usr/bin/python3: the
// script of the source tree this binary was built from, or the path in an environment variable
// (for an installed copy). Arguments are passed as single-quoted shell words.
#include <string>
#include <vector>

namespace crashlink::apps {

/// Runs tools/<script> with `args`; env_override, if set in the environment, names the script
/// instead. Returns 0, or 4 after printing to stderr that `who` failed and what it needs.
int run_python_script(const std::string& script, const char* env_override,
                      const std::vector<std::string>& args, const char* who);

}  // namespace crashlink::apps
