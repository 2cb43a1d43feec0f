#pragma once
// A stable fingerprint of a scenario, exchanged in the protocol's hello (DESIGN.md §3) so that a
// coordinator and its daemons refuse to run different scenarios together.
#include <cstdint>
#include <string>

namespace crashlink::io {

class YamlTree;

/// FNV-1a 64-bit hash of the scenario's canonical text, as 16 lower-case hex digits. The
/// canonical text is the parsed YAML tree written back in one fixed form (mappings in document
/// order, scalars as written), so comments, blank lines, indentation and flow/block style do
/// not change the hash; any changed key or value does. Throws InputError if the YAML is malformed.
std::string scenario_hash_of_text(const std::string& yaml_text,
                                  const std::string& name_for_messages = "<scenario>");

/// The same of an already parsed scenario (read_scenario_with_hash: one parse for both).
std::string scenario_hash_of_tree(const YamlTree& tree);

/// scenario_hash_of_text of the file at `path` (InputError if it cannot be read).
std::string scenario_hash(const std::string& path);

/// FNV-1a 64-bit of raw bytes (offset basis 14695981039346656037, prime 1099511628211).
std::uint64_t fnv1a64(const std::string& bytes);

}  // namespace crashlink::io
