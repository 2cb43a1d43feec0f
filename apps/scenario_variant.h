#pragma once
// A scenario file with one value changed, for commands that run variants of a scene (`sweep
// --refine`: a part's mesh divisions; `advise --process-sample`: a shorter end time). The YAML is
// loaded, the key at `path` replaced and the result written with a first comment line saying
// what changed (the original's comments are dropped).
#include <string>
#include <vector>

namespace crashlink::apps {

/// Writes `out_path`: `scenario` with the scalar at `path` (e.g. {"parts", "wiper_bar", "mesh",
/// "divisions"}) set to `value` (YAML text: "100", "2.0e-3"). Throws InputError when the key is
/// not a scalar that exists in the file, or the output cannot be written.
void write_scenario_variant(const std::string& scenario, const std::vector<std::string>& path,
                            const std::string& value, const std::string& out_path);

}  // namespace crashlink::apps
