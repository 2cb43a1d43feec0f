#pragma once
// Candidate (slave node, segment) pairs in linear time with a uniform bucket grid
// (Benson & Hallquist, "A single surface contact algorithm for the post-buckling analysis of
// shell structures", CMAME 78 (1990): bucket sort of the nodes, each segment searches the
// buckets its box overlaps; Hallquist, LS-DYNA Theory Manual, "Bucket sort").
//
// The candidate predicate (the same for the grid and for the brute-force reference, so both give
// the identical pair set): slave node s and segment i are a pair iff x_s lies in the
// axis-aligned bounding box of segment i's nodes inflated by reach[i] on every side.
//
// Cost: binning the nodes is O(ns); each segment visits the cells its inflated box overlaps,
// O(1) per segment when the cell is about the largest inflated box; the grid is bounded to
// O(ns + nseg) cells (the cell is enlarged if the slave nodes' box would need more).
//
// Layouts: x [3n] interleaved xyz; slaves [ns] node indices; seg_nodes [4 nseg] (triangles repeat
// the third node); reach [nseg] [m]. Result: CSR by slave position k (0..ns-1), segments of
// slave k at segment[offset[k] .. offset[k+1]) in increasing segment index.
#include <cstdint>
#include <vector>

namespace crashlink::contact {

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
  const double* x = nullptr;
  const std::int32_t* slaves = nullptr;
  std::size_t slave_count = 0;
  const std::int32_t* seg_nodes = nullptr;
  const double* reach = nullptr;
  std::size_t segment_count = 0;
};

void bucket_search(const SearchInput& in, CandidateList& out, BucketWork& work);
/// O(ns * nseg) reference with the same predicate (tests only).
void brute_force_search(const SearchInput& in, CandidateList& out);

}  // namespace crashlink::contact
