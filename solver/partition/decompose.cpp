// decompose(): the entry point of crashlink::partition (decomposition.h).
#include "solver/partition/decomposition.h"
#include "solver/partition/partition_detail.h"

namespace crashlink::partition {

const char* scheme_name(Scheme s) {
  return s == Scheme::Layer ? "layer" : "paper";
}

Decomposition decompose(const model::Model& global, Scheme scheme) {
  const detail::Analysis a = detail::analyse(global);
  return scheme == Scheme::Layer ? detail::decompose_layer(a) : detail::decompose_paper(a);
}

}  // namespace crashlink::partition
