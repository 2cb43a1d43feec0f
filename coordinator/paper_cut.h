#pragma once
// What crashlink-coordinator knows of a `paper` run from its own cut of the scenario
// (partition::decompose, Paper; docs/design.md §2.2, §2.5; cosim::paper_nodes), and the checks and
// answers of its start-up:
//   - every daemon's Register must list exactly the coupled nodes this cut gives its domain, in
//     cosim::paper_nodes order (a daemon that read another file, or cut for `layer`, is refused,
//     naming the domain and the first differing node id);
//   - the presences of each node are matched by id (coupling::match_interfaces: positions
//     within 1e-9 of the model size) and their partial masses summed, M = sum_k m^k ([5]);
//   - the fixed steps: coupling::nested_steps over the proposals (split: common; multi:
//     nested, so the fine side lands on every coarse instant, as cosim::PaperRunner needs);
//   - the Setup: M per node, each node's role for [11] (reference or not), the step.
// Daemon indices: the non-empty domains in decomposition order (LayerCut's rule).
#include <cstdint>
#include <vector>

#include "coordinator/layer_cut.h"
#include "coupling/interface_match.h"
#include "coupling/nested_steps.h"
#include "proto/crashlink.pb.h"
#include "solver/cosim/paper_nodes.h"

namespace crashlink::coordinator {

struct PaperCut {
  LayerCut cut;  ///< names, interfaces (their coupled nodes as j_node_ids), end time, size
  std::vector<std::vector<cosim::PaperNodeOfDomain>> nodes;  ///< [daemons] Register order
  std::vector<std::vector<std::int64_t>> node_ids;           ///< [daemons] user ids, same order
};

/// Throws ModelError as layer_cut and paper_nodes do.
PaperCut paper_cut(const model::Model& global, const partition::Decomposition& dec);

/// Checks daemon k's Register (node ids, sizes, a non-negative step). Throws ModelError naming
/// the domain and the node.
void check_paper_register(const PaperCut& cut, int k, const wire::Register& reg);

/// Matches every node's presences by id and sums their masses. Throws InterfaceError / ModelError.
coupling::InterfaceTable match_paper(const PaperCut& cut, const std::vector<wire::Register>& regs);

/// Daemon k's Setup: summed masses and roles in its Register order, its step.
/// end_ticks: the run's end instant (PaperExchange::end_ticks).
wire::Envelope paper_setup(const PaperCut& cut, const coupling::InterfaceTable& table,
                           const coupling::StepPlan& plan, int k, bool common,
                           const wire::Options& options, std::int64_t ticks_per_second,
                           coupling::Tick end_ticks);

}  // namespace crashlink::coordinator
