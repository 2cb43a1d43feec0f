#include "apps/scenario_variant.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <fstream>

#include "core/errors.h"

namespace crashlink::apps {

void write_scenario_variant(const std::string& scenario, const std::vector<std::string>& path,
                            const std::string& value, const std::string& out_path) {
  const std::string key = fmt::format("{}", fmt::join(path, "."));
  YAML::Node root = YAML::LoadFile(scenario);
  // Walk with copies of the handles (YAML::Node is a reference: assigning one would re-seat it).
  std::vector<YAML::Node> chain{root};
  for (const auto& k : path) {
    const YAML::Node& at = chain.back();
    if (!at.IsMap() || !at[k]) {
      throw InputError(fmt::format("{}: no key `{}` (looked for `{}`)", scenario, k, key));
    }
    chain.push_back(at[k]);
  }
  if (!chain.back().IsScalar()) {
    throw InputError(
        fmt::format("{}: `{}` is not a single value; only a scalar can be varied", scenario, key));
  }
  chain.back() = value;  // emitted as a plain scalar: read back as the number it spells
  std::ofstream out(out_path);
  out << "# " << scenario << " with " << key << " = " << value << " (a crashlink variant)\n"
      << root << "\n";
  if (!out) throw InputError(fmt::format("cannot write the scenario variant {}", out_path));
}

}  // namespace crashlink::apps
