#pragma once
// A domain's elements cut into fixed chunks, the unit of work of the solver's threads, and the
// scatter plan under which chunks computed at once add their forces as one thread would, to the
// bit (docs/threads.md).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::integration {

/// Elements per chunk (a multiple of elements::kElementBatch): small enough that two threads
/// finish a cycle's loop within a chunk's time of each other, large enough that few nodes sit
/// on a chunk boundary. Fixed, not derived from the thread count: the energy increments are
/// summed per chunk, then over chunks in order, so a different cut would change their last bits.
inline constexpr std::size_t kChunkElements = 512;

/// Elements [first, end) of part `part`; their corners on shared nodes write slots
/// [slot_first, slot_end) (ElementChunks::scatter).
struct ElementChunk {
  std::size_t part = 0;
  std::size_t first = 0, end = 0;
  std::size_t slot_first = 0, slot_end = 0;
};

/// Two spans of chunks, as Solver::compute_forces runs them: span 0 the interior elements of
/// every part ([0, split[p])), span 1 the rim ([split[p], ne)); in part order, then element order.
///
/// Why the forces stay those of one thread: one thread adds element e's corner forces into its
/// nodes in element order. A node that only one chunk touches gets its additions from that chunk
/// alone, in that order, whoever runs it. A node that several chunks of a span touch is shared:
/// every corner on it adds into a slot of its own instead (zeroed by its chunk first), and
/// replay() then adds the slots into the node in (part, element, corner) order, the order one
/// thread adds them in; x + 0 + c = x + c exactly, so a slot holds exactly its contribution.
class ElementChunks {
 public:
  /// `split[p]`: the first rim element of part p (a multiple of kElementBatch or ne);
  /// `deformable[p]`: false for rigid parts (no chunks). `concurrent`: build the scatter plan
  /// (with one thread the elements add into their nodes directly: the same bits).
  void build(const model::Model& m, const std::vector<std::size_t>& split,
             const std::vector<std::uint8_t>& deformable, bool concurrent);

  const std::vector<ElementChunk>& chunks(int span) const { return span_[span].chunks; }
  /// [k ne] of part p, or null (no scatter plan): elements::StepInfo::scatter.
  const std::int32_t* scatter(std::size_t p) const {
    return scatter_.empty() || scatter_[p].empty() ? nullptr : scatter_[p].data();
  }
  double* f_slots() { return f_slot_.data(); }
  double* m_slots() { return m_slot_.data(); }
  /// Zeroes the slots of chunk c of span (its task does it before its kernel call).
  void clear_slots(const ElementChunk& c);
  /// Shared nodes of span (replay() runs over [0, shared_nodes(span)) in any split).
  std::size_t shared_nodes(int span) const { return span_[span].node.size(); }
  /// For shared nodes [i0, i1) of span: f[node] += its slots in order (m alike).
  void replay(int span, std::size_t i0, std::size_t i1, double* f, double* m) const;

 private:
  struct Span {
    std::vector<ElementChunk> chunks;
    std::vector<std::int32_t> node;  ///< shared nodes, ascending
    std::vector<std::size_t> start;  ///< [node.size() + 1] into slot
    std::vector<std::int32_t> slot;  ///< each shared node's slots, ascending
  };
  Span span_[2];
  std::vector<std::vector<std::int32_t>> scatter_;  ///< [parts][k ne] or empty
  std::vector<double> f_slot_, m_slot_;             ///< [3 slots]
};

}  // namespace crashlink::integration
