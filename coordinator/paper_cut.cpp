// The coordinator's cut of a `paper` run (paper_cut.h).
#include "coordinator/paper_cut.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace crashlink::coordinator {

PaperCut paper_cut(const model::Model& global, const partition::Decomposition& dec) {
  PaperCut p;
  p.cut = layer_cut(global, dec);
  for (const int d : p.cut.domain_index) {
    p.nodes.push_back(cosim::paper_nodes(dec, d));
    auto& ids = p.node_ids.emplace_back();
    for (const auto& n : p.nodes.back()) ids.push_back(global.nodes.id[n.global]);
  }
  return p;
}

void check_paper_register(const PaperCut& cut, int k, const wire::Register& reg) {
  const auto ku = static_cast<std::size_t>(k);
  const std::string& name = cut.cut.names[ku];
  const auto& want = cut.node_ids[ku];
  if (reg.layer_interfaces_size() > 0)
    throw ModelError(fmt::format(
        "domain '{}' registered {} `layer` interfaces, but this coordinator runs `paper`: start "
        "its crashlink-solver with --coupling paper too",
        name, reg.layer_interfaces_size()));
  const auto n = static_cast<std::size_t>(reg.node_ids_size());
  for (std::size_t j = 0; j < std::max(n, want.size()); ++j) {
    const bool have = j < n, expected = j < want.size();
    if (have && expected && reg.node_ids(static_cast<int>(j)) == want[j]) continue;
    throw ModelError(fmt::format(
        "domain '{}' registered coupled node {} as {}; the coordinator's `paper` cut has {} there "
        "({} nodes registered, {} expected): do the daemon and the coordinator run the same "
        "build on the same scenario, both with --coupling paper?",
        name, j,
        have ? fmt::format("id {}", reg.node_ids(static_cast<int>(j))) : std::string("missing"),
        expected ? fmt::format("node id {}", want[j]) : std::string("no node"), n, want.size()));
  }
  if (static_cast<std::size_t>(reg.masses_kg_size()) != n ||
      static_cast<std::size_t>(reg.positions_m_size()) != 3 * n)
    throw ModelError(
        fmt::format("domain '{}' registered {} coupled nodes, {} masses and {} "
                    "position values",
                    name, n, reg.masses_kg_size(), reg.positions_m_size()));
  if (reg.stable_step_ticks() < 0)
    throw ModelError(fmt::format("domain '{}' registered a stable step of {} ticks", name,
                                 reg.stable_step_ticks()));
}

coupling::InterfaceTable match_paper(const PaperCut& cut, const std::vector<wire::Register>& regs) {
  std::vector<coupling::DomainInterface> all(regs.size());
  for (std::size_t k = 0; k < regs.size(); ++k) {
    auto& d = all[k];
    d.domain = cut.cut.names[k];
    d.node_ids.assign(regs[k].node_ids().begin(), regs[k].node_ids().end());
    d.masses_kg.assign(regs[k].masses_kg().begin(), regs[k].masses_kg().end());
    d.positions_m.assign(regs[k].positions_m().begin(), regs[k].positions_m().end());
  }
  auto table = coupling::match_interfaces(all, 1e-9 * cut.cut.size_m);
  for (const auto& node : table.nodes)
    if (node.copies.size() != 2)
      throw ModelError(fmt::format(
          "paper: node id {} is present in {} domains; the scheme couples each node between two "
          "(cut the model so that no node is shared by three domains)",
          node.id, node.copies.size()));
  return table;
}

wire::Envelope paper_setup(const PaperCut& cut, const coupling::InterfaceTable& table,
                           const coupling::StepPlan& plan, int k, bool common,
                           const wire::Options& options, std::int64_t ticks_per_second,
                           coupling::Tick end_ticks) {
  wire::Envelope e = setup_envelope(common, "paper", options, ticks_per_second, end_ticks);
  auto* s = e.mutable_setup();
  s->set_step_ticks(plan.step[static_cast<std::size_t>(k)]);
  const auto M = table.summed_masses(k);
  s->mutable_summed_masses_kg()->Add(M.begin(), M.end());
  for (const auto& n : cut.nodes[static_cast<std::size_t>(k)])
    s->add_node_roles(n.reference ? wire::NODE_ROLE_REFERENCE : wire::NODE_ROLE_NON_REFERENCE);
  return e;
}

}  // namespace crashlink::coordinator
