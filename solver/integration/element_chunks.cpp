#include "solver/integration/element_chunks.h"

#include <algorithm>

#include "core/errors.h"
#include "solver/elements/kernel_io.h"

namespace crashlink::integration {

static_assert(kChunkElements % elements::kElementBatch == 0,
              "a chunk must start on a kernel batch");

void ElementChunks::build(const model::Model& m, const std::vector<std::size_t>& split,
                          const std::vector<std::uint8_t>& deformable, bool concurrent) {
  const std::size_t n = m.nodes.count();
  const std::size_t parts = m.parts.size();
  for (int s = 0; s < 2; ++s) {
    auto& sp = span_[s];
    sp = Span{};
    for (std::size_t p = 0; p < parts; ++p) {
      if (!deformable[p]) continue;
      const std::size_t ne = m.parts[p].element_count();
      const std::size_t lo = s == 0 ? 0 : split[p], hi = s == 0 ? split[p] : ne;
      for (std::size_t e = lo; e < hi; e += kChunkElements)
        sp.chunks.push_back({p, e, std::min(hi, e + kChunkElements), 0, 0});
    }
  }
  scatter_.clear();
  f_slot_.clear();
  m_slot_.clear();
  if (!concurrent) return;
  scatter_.resize(parts);
  for (std::size_t p = 0; p < parts; ++p)
    if (deformable[p]) scatter_[p].assign(m.parts[p].connectivity.size(), 0);
  std::vector<std::int64_t> last_chunk(n);
  std::vector<std::uint8_t> shared(n);
  std::size_t slots = 0;
  for (auto& sp : span_) {
    // shared: touched by two chunks of the span or more
    std::fill(last_chunk.begin(), last_chunk.end(), -1);
    std::fill(shared.begin(), shared.end(), 0);
    for (std::size_t c = 0; c < sp.chunks.size(); ++c) {
      const auto& ch = sp.chunks[c];
      const auto& part = m.parts[ch.part];
      const auto k = static_cast<std::size_t>(model::nodes_per_element(part.kind));
      for (std::size_t j = k * ch.first; j < k * ch.end; ++j) {
        const auto i = static_cast<std::size_t>(part.connectivity[j]);
        if (last_chunk[i] >= 0 && last_chunk[i] != static_cast<std::int64_t>(c)) shared[i] = 1;
        last_chunk[i] = static_cast<std::int64_t>(c);
      }
    }
    // slots in (part, element, corner) order; the scatter plan
    std::vector<std::int32_t> slot_node;
    for (auto& ch : sp.chunks) {
      const auto& part = m.parts[ch.part];
      const auto k = static_cast<std::size_t>(model::nodes_per_element(part.kind));
      ch.slot_first = slots;
      for (std::size_t j = k * ch.first; j < k * ch.end; ++j) {
        const std::int32_t node = part.connectivity[j];
        if (shared[static_cast<std::size_t>(node)]) {
          if (slots >= static_cast<std::size_t>(INT32_MAX))
            throw ModelError(
                "too many element corners on chunk boundaries for a 32-bit scatter "
                "plan; run this domain with one thread");
          scatter_[ch.part][j] = -1 - static_cast<std::int32_t>(slots);
          slot_node.push_back(node);
          ++slots;
        } else {
          scatter_[ch.part][j] = node;
        }
      }
      ch.slot_end = slots;
    }
    // each shared node's slots, ascending (a counting sort keeps the slot order)
    const std::size_t base = slots - slot_node.size();
    std::vector<std::size_t> count(n + 1, 0);
    for (auto node : slot_node) ++count[static_cast<std::size_t>(node) + 1];
    for (std::size_t i = 0; i < n; ++i)
      if (count[i + 1] > 0) sp.node.push_back(static_cast<std::int32_t>(i));
    for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
    sp.slot.resize(slot_node.size());
    std::vector<std::size_t> fill(count.begin(), count.end() - 1);
    for (std::size_t s = 0; s < slot_node.size(); ++s)
      sp.slot[fill[static_cast<std::size_t>(slot_node[s])]++] = static_cast<std::int32_t>(base + s);
    sp.start.clear();
    for (auto node : sp.node) sp.start.push_back(count[static_cast<std::size_t>(node)]);
    sp.start.push_back(slot_node.size());
  }
  f_slot_.assign(3 * slots, 0.0);
  m_slot_.assign(3 * slots, 0.0);
}

void ElementChunks::clear_slots(const ElementChunk& c) {
  if (f_slot_.empty() || c.slot_end == c.slot_first) return;
  std::fill(f_slot_.begin() + static_cast<std::ptrdiff_t>(3 * c.slot_first),
            f_slot_.begin() + static_cast<std::ptrdiff_t>(3 * c.slot_end), 0.0);
  std::fill(m_slot_.begin() + static_cast<std::ptrdiff_t>(3 * c.slot_first),
            m_slot_.begin() + static_cast<std::ptrdiff_t>(3 * c.slot_end), 0.0);
}

void ElementChunks::replay(int span, std::size_t i0, std::size_t i1, double* f, double* m) const {
  const auto& sp = span_[span];
  const double* __restrict fs = f_slot_.data();
  const double* __restrict ms = m_slot_.data();
  for (std::size_t j = i0; j < i1; ++j) {
    const std::size_t k = 3 * static_cast<std::size_t>(sp.node[j]);
    double f0 = f[k], f1 = f[k + 1], f2 = f[k + 2];
    double m0 = m[k], m1 = m[k + 1], m2 = m[k + 2];
    for (std::size_t s = sp.start[j]; s < sp.start[j + 1]; ++s) {
      const std::size_t q = 3 * static_cast<std::size_t>(sp.slot[s]);
      f0 += fs[q];
      f1 += fs[q + 1];
      f2 += fs[q + 2];
      m0 += ms[q];
      m1 += ms[q + 1];
      m2 += ms[q + 2];
    }
    f[k] = f0;
    f[k + 1] = f1;
    f[k + 2] = f2;
    m[k] = m0;
    m[k + 1] = m1;
    m[k + 2] = m2;
  }
}

}  // namespace crashlink::integration
