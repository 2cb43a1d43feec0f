#pragma once
// What crashlink-coordinator knows of a `layer` run from its own cut of the scenario
// (partition::decompose, Layer; docs/design.md §2.7 "How to distribute layer"), and the checks and
// answers of its start-up:
//   - every daemon's Register must describe the interfaces this cut gives its domain: same
//     interface indices and sides, the same J node ids in the same order (a daemon that read
//     another file, or another build that cuts differently, is refused naming the domain and the
//     first differing node id); the two sides' copies of J are matched by id with
//     coupling::match_interfaces (positions within a tolerance, J's mass on the owner);
//   - the fixed steps: coupling::nested_steps over the registered proposals and the
//     interfaces' (coarse, fine) pairs (split: common; multi: nested), exactly as
//     cosim::LayerNetwork plans them, so a distributed run reproduces it bit for bit;
//   - the Setup of each daemon: its step, every interface with the partner's step.
// Daemon indices: the non-empty domains in decomposition order (LayerDomains::solvers order).
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/nested_steps.h"
#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::coordinator {

struct CutInterface {
  std::uint32_t index = 0;               ///< Decomposition::interfaces index
  int fine = -1;                         ///< daemon index of the fine side (holds the layer)
  int coarse = -1;                       ///< daemon index of the coarse side (owns J)
  std::vector<std::int64_t> j_node_ids;  ///< user ids of J, Interface::j_nodes_global order
  std::string kind;                      ///< "link", "contact:<name>", ...
  std::string name;                      ///< "<fine>-<coarse>" (+ "-<index>" if not unique)
};

struct LayerCut {
  std::vector<std::string> names;  ///< [daemons] domain names
  std::vector<int> domain_index;   ///< [daemons] index into Decomposition::domains
  std::vector<CutInterface> interfaces;
  double end_time_s = 0.0;
  double size_m = 1.0;  ///< model diagonal (position tolerance scale)
};

/// Throws ModelError when the cut has fewer than one non-empty domain or an interface touches an
/// empty domain.
LayerCut layer_cut(const model::Model& global, const partition::Decomposition& dec);

/// Checks daemon k's Register against the cut (the file comment). Throws ModelError naming
/// the domain, the interface and the node id.
void check_register(const LayerCut& cut, int k, const wire::Register& reg);

/// Matches the two sides of every interface (coupling::match_interfaces): positions within
/// 1e-9 of the model size, J's mass positive. Throws InterfaceError / ModelError.
void match_sides(const LayerCut& cut, const std::vector<wire::Register>& regs);

/// The fixed steps from the registered proposals (Register.stable_step_ticks; 0: no limit).
/// `lts_variable_tps` > 0 (the ticks per second): `lts` with variable steps, whose plan is the
/// first owner step: planned from the proposals the steppers' cost rule sees at t = 0
/// (coupling::lts_variable_first_proposals; the followers' from Register.stable_step_s, the costs
/// the registered element counts).
coupling::StepPlan plan_steps(const LayerCut& cut, const std::vector<wire::Register>& regs,
                              bool common, std::int64_t lts_variable_tps = 0);

/// A Setup with the fields every scheme's carries: mode, coupling, options, tick, end instant.
wire::Envelope setup_envelope(bool common, const std::string& scheme, const wire::Options& options,
                              std::int64_t ticks_per_second, coupling::Tick end_ticks);

/// Daemon k's Setup (`scheme`: "layer" or "lts", the stepper's form).
wire::Envelope setup_message(const LayerCut& cut, const coupling::StepPlan& plan, int k,
                             bool common, const wire::Options& options,
                             std::int64_t ticks_per_second, const std::string& scheme = "layer");

}  // namespace crashlink::coordinator
