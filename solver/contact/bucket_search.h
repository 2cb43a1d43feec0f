#pragma once
// Candidate (slave node, segment) pairs in linear time with a uniform bucket grid
// (Benson & Hallquist, "A single surface contact algorithm for the post-buckling analysis of
// shell structures", CMAME 78 (1990): bucket sort of the nodes, each segment searches the
// buckets its box overlaps; Hallquist, LS-DYNA Theory Manual, "Bucket sort"). The predicate and
// the cost are on bucket_search.
#include <cstdint>
#include <vector>

namespace crashlink::contact {

/// CSR by slave position k (0..ns-1): the segments of slave k at
/// segment[offset[k] .. offset[k+1]) in increasing segment index.
struct CandidateList {
  std::vector<std::int32_t> offset;   ///< [ns + 1]
  std::vector<std::int32_t> segment;  ///< [pairs]
  std::size_t pairs() const { return segment.size(); }
};

/// Scratch buffers kept between sorts (no allocation once warm).
struct BucketWork {
  std::vector<std::int32_t> cell_start, cell_nodes, pair_slave, pair_seg, count;
};

struct SearchInput {
  const double* x = nullptr;                ///< [3n] interleaved xyz [m]
  const std::int32_t* slaves = nullptr;     ///< [ns] node indices
  std::size_t slave_count = 0;              ///< ns
  const std::int32_t* seg_nodes = nullptr;  ///< [4 nseg] (triangles repeat the third node)
  const double* reach = nullptr;            ///< [nseg] [m]
  std::size_t segment_count = 0;            ///< nseg
};

/// The candidate pairs. Predicate (the same for the grid and for the brute-force reference, so
/// both give the identical pair set): slave node s and segment i are a pair iff x_s lies in the
/// axis-aligned bounding box of segment i's nodes inflated by reach[i] on every side.
/// Cost: binning the nodes is O(ns); each segment visits the cells its inflated box overlaps,
/// O(1) per segment when the cell is about the largest inflated box; the grid is bounded to
/// O(ns + nseg) cells (the cell is enlarged if the slave nodes' box would need more).
void bucket_search(const SearchInput& in, CandidateList& out, BucketWork& work);
/// O(ns * nseg) reference with the same predicate (tests only).
void brute_force_search(const SearchInput& in, CandidateList& out);

}  // namespace crashlink::contact
