#pragma once
// A stable fingerprint of a scenario, exchanged in the protocol's hello (docs/design.md §3) so that
// a coordinator and its daemons refuse to run different scenarios together.
#include <cstdint>
#include <string>
#include <vector>

namespace crashlink::io {

class YamlTree;

/// FNV-1a 64-bit hash of the scenario's canonical text, as 16 lower-case hex digits. The
/// canonical text is the parsed YAML tree written back in one fixed form (mappings in document
/// order, scalars as written), so comments, blank lines, indentation and flow/block style do
/// not change the hash; any changed key or value does. Throws InputError if the YAML is malformed.
std::string scenario_hash_of_text(const std::string& yaml_text,
                                  const std::string& name_for_messages = "<scenario>");

/// The same of an already parsed scenario (read_scenario_with_hash: one parse for both).
/// Covers the YAML only: a keyword deck the scenario names is added by finish_scenario_hash.
std::string scenario_hash_of_tree(const YamlTree& tree);

/// The hash in two steps, for a scenario that names other files (`model: {deck: car.k}`): the
/// tree, then the bytes of every file it reads (the deck and its *INCLUDEs, in reading order;
/// their paths are not hashed, so the same files at other paths on another host agree). With no
/// file, finish_scenario_hash equals scenario_hash_of_tree.
struct HashOfTree {
  std::uint64_t state = 0;
};
HashOfTree begin_scenario_hash(const YamlTree& tree);
/// InputError if a file cannot be read.
std::string finish_scenario_hash(const HashOfTree& tree_hash,
                                 const std::vector<std::string>& files);

/// The hash of the scenario file at `path` (InputError if it cannot be read): its tree, and for
/// a scenario naming a keyword deck the deck's files too (it is then read:
/// read_scenario_with_hash).
std::string scenario_hash(const std::string& path);

/// FNV-1a 64-bit of raw bytes (offset basis 14695981039346656037, prime 1099511628211).
std::uint64_t fnv1a64(const std::string& bytes);

}  // namespace crashlink::io
