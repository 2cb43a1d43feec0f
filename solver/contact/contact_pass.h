#pragma once
// One pass of a contact: a set of nodes against a set of segments (contact_interface.cpp says
// how passes make one-pass, two-pass and single-surface contact). Search, pair selection and
// penalty forces per cycle; the formulas are on the functions in contact_pass.cpp.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/contact/bucket_search.h"
#include "solver/contact/friction.h"
#include "solver/contact/node_properties.h"
#include "solver/contact/projection.h"
#include "solver/contact/segments.h"

namespace crashlink::contact {

/// The pair stiffness rule (contact_pass.cpp, pair_stiffness) and what it needs.
struct StiffnessRule {
  bool soft = true;         ///< also k_soft = soft_scale m_eff / dt0^2
  double soft_scale = 0.1;  ///< LS-DYNA SOFSCL
  double dt0_s = 0.0;       ///< the domain's stable step at the start (0: not known yet)
};

/// The forces one compute() applied (node, force xyz [N]): the interface's work over the next
/// step comes from them (ContactStep::energy_J).
struct AppliedForces {
  std::vector<std::int32_t> node;
  std::vector<double> force_N;  ///< [3 entries]
  /// Starts a cycle's record. With v (v^{n+1/2} [3n], dt > 0), sum_new() sums the power F . v
  /// of the entries while they are in cache (summed_work): what work(v, dt) gives over the
  /// whole record, without a second pass over it (~140 B per active node: at 1M nodes the record
  /// streams from memory).
  void clear(const double* v = nullptr) {
    node.clear();
    force_N.clear();
    v_ = v;
    power_W_ = 0.0;
    summed_ = 0;
  }
  /// f[node] += scale F, recorded. The product is rounded once and both uses take it: what f
  /// gains is what the record says (a product written twice may be fused into the addition, an
  /// FMA, where F may alias f and the compiler reads it again after the store).
  void apply(double* f, std::int32_t i, const double* F, double scale) {
    double* fi = f + 3 * static_cast<std::size_t>(i);
    node.push_back(i);
    for (int a = 0; a < 3; ++a) {
      const double c = scale * F[a];
      force_N.push_back(c);
      fi[a] += c;
    }
  }
  /// dt sum of F . v over the entries (v = v^{n+1/2}: dt v = u^{n+1} - u^n) [J].
  double work(const double* v, double dt) const;
  /// Adds the power of the entries made since the last call (nothing without v) [W].
  void sum_new() {
    if (v_) power_W_ = sum_power(v_, summed_, power_W_);
    summed_ = node.size();
  }
  /// dt sum of F . v over the entries since clear(v), in entry order [J]: equals work(v, dt)
  /// bit for bit (the same loop, the same order, one accumulator carried along). Both are out of
  /// line so that the product with dt is rounded before the caller adds it (inlined, it could be
  /// fused into an FMA with the sum and change the last bit of the energy).
  double summed_work(double dt);

 private:
  /// w + sum of F . v over the entries e0.. in order. Out of line: one compiled loop for both
  /// uses (inlined, the compiler may contract F . v into FMAs differently per call site, and the
  /// last bits of the energy would depend on it).
  [[gnu::noinline]] double sum_power(const double* v, std::size_t e0, double w) const;
  const double* v_ = nullptr;
  double power_W_ = 0.0;
  std::size_t summed_ = 0;
};

/// What a pass adds to the interface's step: resultant on its nodes, pairs, potential.
struct PassResult {
  double resultant_N[3] = {0.0, 0.0, 0.0};
  std::int64_t active_pairs = 0;
  double potential_J = 0.0;
};

class ContactPass {
 public:
  /// `nodes` the pass's (slave) nodes, `seg` its segments; `self`: single-surface, the
  /// segments of each node's own elements and their neighbours are skipped.
  /// `node_half_thickness_m` > 0: the offset of every node of a shell (half_thickness_m > 0)
  /// in place of its own (a contact thickness, LS-DYNA SST/MST).
  ContactPass(const model::Model& m, std::vector<std::int32_t> nodes, SegmentSet seg,
              const NodeProperties& np, bool self, double node_half_thickness_m = 0.0);

  /// One cycle of the pass at configuration x (t^{n+1}) with mid-step velocities v, in three
  /// steps (contact_pass.cpp, compute_block): prepare() (the travel, a new sort when due), then
  /// compute_block(b) for every block b < block_count(), on any thread in any order, then
  /// apply_blocks() adds their forces into f in block order: the same bits for any order.
  void prepare(const double* x, const double* v, double dt);
  std::size_t block_count() const { return blocks_.size(); }
  void compute_block(std::size_t b, const double* x, const double* v, double dt,
                     const FrictionLaw& friction, const StiffnessRule& rule);
  void apply_blocks(double* f, AppliedForces& applied, PassResult& out);
  /// Nodes per block: the unit a thread takes.
  static constexpr std::size_t kBlockNodes = 64;
  /// Smallest m_eff / k over the candidate pairs [s^2] (infinity without candidates).
  double min_mass_over_stiffness(const StiffnessRule& rule);
  /// Largest k / m_eff any pair could have [1/s^2] (contact_pass.cpp).
  double max_stiffness_over_mass(const StiffnessRule& rule) const;

  void save_state(core::StateWriter& w, const std::string& prefix) const;
  void restore_state(const core::StateReader& r, const std::string& prefix,
                     const std::string& name);

  std::int64_t sorts = 0;
  std::int64_t slept = 0;  ///< node tests skipped by sleeping nodes (diagnostics)
  std::size_t segment_count() const { return seg_.size(); }
  std::size_t node_count() const { return nodes_.size(); }
  const std::vector<std::int32_t>& nodes() const { return nodes_; }
  const SegmentSet& segments() const { return seg_; }

 private:
  double pair_stiffness(std::size_t k, std::size_t i, double m_eff,
                        const StiffnessRule& rule) const;
  void sort(const double* x);
  bool classify(std::size_t k, std::size_t i, const double* xa, const double* p, Projection& pr,
                double& g, double* dir, int& side, double& dist) const;
  struct Hit {  // one candidate's verdict (compute_block)
    double g = 0.0, dist = 0.0;
    double dir[3] = {0.0, 0.0, 0.0};
    Projection pr;
    std::size_t i = 0;
    int side = 0;
  };
  /// One block of kBlockNodes nodes: its scratch, and what its nodes add, in node order, for
  /// apply_blocks() to apply after every block is done (vectors kept between calls: no allocation
  /// once they have grown). A cache line of its own: two threads on neighbouring blocks would
  /// otherwise write into one line at every hit (false sharing).
  struct alignas(64) Block {
    std::vector<Hit> hits, pair, opposing, second;
    struct Entry {
      std::int32_t node;    ///< where the force goes
      std::int32_t spring;  ///< whose force F it is: an index into `spring`
      double scale;         ///< the share of F: 1 on the node, -N_a / (group size) on a segment's
    };
    std::vector<Entry> entry;  ///< the forces, in the order one thread applies them
    /// [5 per spring] its potential's factors 1/2 k g [N] and g [m] (their product: the
    /// potential 1/2 k g^2 [J]), then F [N]
    std::vector<double> spring;
    std::int64_t active_pairs = 0, slept = 0;
  };
  std::vector<Block> blocks_;
  bool share_node(std::size_t i, std::size_t j) const;
  void nearest(const std::vector<Hit>& in, std::vector<Hit>& out) const;
  bool penetrating(const std::vector<Hit>& group) const;
  static void mean_direction(const std::vector<Hit>& group, double* dir);
  void push(std::size_t k, const std::vector<Hit>& group, const double* dir, const double* v,
            double dt, const FrictionLaw& friction, const StiffnessRule& rule, Block& out,
            bool first);
  std::vector<std::array<std::int64_t, 4>> seg_key_;  // [nseg] sorted node ids: tie order
  double gap_cap_m_ = 0.0;  // least depth of the one-sided faces [m] (classify)

  SegmentSet seg_;
  std::vector<std::int32_t> nodes_;      // [ns]
  std::vector<double> node_offset_m_;    // [ns]
  std::vector<double> node_k_N_m_;       // [ns]
  std::vector<double> node_mass_kg_;     // [ns]
  std::vector<double> seg_mass_kg_;      // [nseg]
  std::vector<double> reach_m_;          // [nseg] box inflation for the search
  std::vector<double> contact_reach_m_;  // [nseg] box inflation for contact
  std::vector<double> seg_size_m_;       // [nseg] sqrt of the reference area
  std::vector<std::int32_t> moving_;     // nodes whose speed bounds the travel
  // single surface: segments skipped for node k, excluded_[excl_offset_[k] .. [k+1]) sorted
  bool self_ = false;
  std::vector<std::int32_t> excl_offset_, excluded_;
  double margin_m_ = 0.0;
  double travelled_m_ = 0.0;
  bool need_sort_ = true;
  CandidateList cand_;
  BucketWork work_;
  std::vector<double> ft_N_;            // [3 ns] friction history
  std::vector<std::int8_t> side_;       // [ns] shell side while in contact (+1, -1; 0 = none)
  std::vector<std::int32_t> side_seg_;  // [ns] the segment side_ was taken on (-1: any)
  std::vector<double> wake_m_;          // [ns] sleeping until travelled_m_ reaches this
  // min m_eff / k over the candidates, cached per sort (and dt0, which is set once)
  double min_ratio_ = 0.0;
  std::int64_t min_ratio_sorts_ = -1;
  double min_ratio_dt0_ = -1.0;
};

}  // namespace crashlink::contact
