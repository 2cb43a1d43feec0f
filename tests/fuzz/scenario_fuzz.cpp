// libFuzzer target: the scenario reader (docs/fuzzing.md). Input: YAML text, read as
// crashlink-coordinator and crashlink-solver read a scenario file: io::scenario_hash_of_text
// (the Hello's hash), io::parse_scenario (every section, the mesh generators, model::validate),
// then the `layer` cut (partition::decompose) when the scenario has domains (and at most
// kMaxCutElements elements).
// Expected failures: InputError (scenario_reader.h: every mistake in the input throws it, at its
// line), ModelError from the cut (a decomposition that cannot be run). Anything else escapes and
// is a bug.
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"
#include "solver/partition/decomposition.h"
#include "tests/fuzz/fuzz_verbose.h"

namespace {
constexpr std::size_t kMaxCutElements = 20000;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace crashlink;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)io::scenario_hash_of_text(text, "fuzz.yaml");
    const auto model = io::parse_scenario(text, "fuzz.yaml");
    // Work bound per input: the cut of a model near the reader's 1e6-element limit takes longer
    // than the 10 s timeout under ASan (a big model, not a bug); small models are cut.
    if (!model.domains.empty() && model.element_count() <= kMaxCutElements)
      (void)partition::decompose(model, partition::Scheme::Layer);
  } catch (const InputError& e) {
    fuzz::report(e);
  } catch (const ModelError& e) {
    fuzz::report(e);
  }
  return 0;
}
