// decompose(): the entry point of crashlink::partition (decomposition.h).
#include <fmt/format.h>

#include "core/errors.h"
#include "solver/partition/decomposition.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition {

const char* scheme_name(Scheme s) {
  return s == Scheme::Layer ? "layer" : "paper";
}

Decomposition decompose(const model::Model& global, Scheme scheme, int overlap_layers) {
  if (overlap_layers < 0 || overlap_layers > 16 || (scheme == Scheme::Paper && overlap_layers != 0))
    throw ModelError(fmt::format(
        "decomposition: {} overlap layers; the layer cut takes 0 to 16 (the lts scheme's "
        "overlap), the paper cut none",
        overlap_layers));
  const detail::Analysis a = detail::analyse(global);
  return scheme == Scheme::Layer ? detail::decompose_layer(a, overlap_layers)
                                 : detail::decompose_paper(a);
}

}  // namespace crashlink::partition
