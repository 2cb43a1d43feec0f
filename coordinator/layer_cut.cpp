#include "coordinator/layer_cut.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/errors.h"
#include "coupling/interface_match.h"
#include "coupling/step_policy.h"

namespace crashlink::coordinator {

LayerCut layer_cut(const model::Model& global, const partition::Decomposition& dec) {
  LayerCut cut;
  std::vector<int> daemon_of(dec.domains.size(), -1);
  for (std::size_t d = 0; d < dec.domains.size(); ++d) {
    if (dec.domains[d].empty()) continue;
    daemon_of[d] = static_cast<int>(cut.names.size());
    cut.names.push_back(dec.domains[d].name);
    cut.domain_index.push_back(static_cast<int>(d));
  }
  if (cut.names.empty()) throw ModelError("coordinator: the scenario's cut has no domain");
  std::map<std::string, int> seen;
  for (std::size_t i = 0; i < dec.interfaces.size(); ++i) {
    const auto& itf = dec.interfaces[i];
    CutInterface c;
    c.index = static_cast<std::uint32_t>(i);
    c.fine = daemon_of[static_cast<std::size_t>(itf.fine)];
    c.coarse = daemon_of[static_cast<std::size_t>(itf.coarse)];
    if (c.fine < 0 || c.coarse < 0) {
      throw ModelError(
          fmt::format("coordinator: interface {} ({}) joins an empty domain", i, itf.kind));
    }
    for (const auto g : itf.j_nodes_global) {
      c.j_node_ids.push_back(global.nodes.id[static_cast<std::size_t>(g)]);
    }
    c.kind = itf.kind;
    c.name = cut.names[static_cast<std::size_t>(c.fine)] + "-" +
             cut.names[static_cast<std::size_t>(c.coarse)];
    cut.interfaces.push_back(std::move(c));
    ++seen[cut.interfaces.back().name];
  }
  for (auto& c : cut.interfaces) {
    if (seen[c.name] > 1) c.name += fmt::format("-{}", c.index);
  }
  cut.end_time_s = global.controls.end_time_s;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t n = 0; n < global.nodes.count(); ++n) {
    for (std::size_t d = 0; d < 3; ++d) {
      const double x = global.nodes.x0[3 * n + d];
      lo[d] = n == 0 ? x : std::min(lo[d], x);
      hi[d] = n == 0 ? x : std::max(hi[d], x);
    }
  }
  cut.size_m = std::max(1e-3, std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
  return cut;
}

void check_register(const LayerCut& cut, int k, const wire::Register& reg) {
  const std::string& name = cut.names[static_cast<std::size_t>(k)];
  std::vector<const CutInterface*> mine;
  for (const auto& c : cut.interfaces) {
    if (c.fine == k || c.coarse == k) mine.push_back(&c);
  }
  if (reg.node_ids_size() > 0) {
    throw ModelError(fmt::format(
        "domain '{}' registered {} `paper` coupled nodes, but this coordinator runs `layer`: start "
        "crashlink-solver and crashlink-coordinator with the same --coupling",
        name, reg.node_ids_size()));
  }
  if (static_cast<std::size_t>(reg.layer_interfaces_size()) != mine.size()) {
    throw ModelError(
        fmt::format("domain '{}' registered {} layer interfaces; the coordinator's "
                    "cut of the scenario gives it {}: do the daemon and the "
                    "coordinator run the same build on the same scenario?",
                    name, reg.layer_interfaces_size(), mine.size()));
  }
  for (const auto& li : reg.layer_interfaces()) {
    const auto it = std::find_if(mine.begin(), mine.end(),
                                 [&](const CutInterface* c) { return c->index == li.index(); });
    if (it == mine.end()) {
      throw ModelError(
          fmt::format("domain '{}' registered interface {}, which is not one of its "
                      "interfaces in the coordinator's cut",
                      name, li.index()));
    }
    const CutInterface& c = **it;
    if (li.fine_side() != (c.fine == k)) {
      throw ModelError(
          fmt::format("domain '{}' registered itself as the {} side of interface {} "
                      "({}); the coordinator's cut makes it the {} side",
                      name, li.fine_side() ? "fine" : "coarse", c.index, c.name,
                      c.fine == k ? "fine" : "coarse"));
    }
    const auto n = static_cast<std::size_t>(li.j_node_ids_size());
    for (std::size_t j = 0; j < std::max(n, c.j_node_ids.size()); ++j) {
      const bool have = j < n, want = j < c.j_node_ids.size();
      if (have && want && li.j_node_ids(static_cast<int>(j)) == c.j_node_ids[j]) continue;
      throw ModelError(fmt::format(
          "domain '{}' registered J node {} of interface {} ({}) as {}; the coordinator's cut has "
          "{} there ({} J nodes registered, {} expected)",
          name, j, c.index, c.name,
          have ? fmt::format("id {}", li.j_node_ids(static_cast<int>(j))) : std::string("missing"),
          want ? fmt::format("node id {}", c.j_node_ids[j]) : std::string("no node"), n,
          c.j_node_ids.size()));
    }
    if (static_cast<std::size_t>(li.masses_kg_size()) != n ||
        static_cast<std::size_t>(li.positions_m_size()) != 3 * n) {
      throw ModelError(
          fmt::format("domain '{}' registered interface {} with {} J nodes, {} "
                      "masses and {} position values",
                      name, c.index, n, li.masses_kg_size(), li.positions_m_size()));
    }
  }
  if (reg.stable_step_ticks() < 0) {
    throw ModelError(fmt::format("domain '{}' registered a stable step of {} ticks", name,
                                 reg.stable_step_ticks()));
  }
}

void match_sides(const LayerCut& cut, const std::vector<wire::Register>& regs) {
  for (const auto& c : cut.interfaces) {
    std::vector<coupling::DomainInterface> sides(2);
    const int ks[2] = {c.coarse, c.fine};
    for (int s = 0; s < 2; ++s) {
      const int k = ks[s];
      sides[static_cast<std::size_t>(s)].domain = cut.names[static_cast<std::size_t>(k)];
      for (const auto& li : regs[static_cast<std::size_t>(k)].layer_interfaces()) {
        if (li.index() != c.index) continue;
        auto& d = sides[static_cast<std::size_t>(s)];
        d.node_ids.assign(li.j_node_ids().begin(), li.j_node_ids().end());
        d.masses_kg.assign(li.masses_kg().begin(), li.masses_kg().end());
        d.positions_m.assign(li.positions_m().begin(), li.positions_m().end());
      }
    }
    coupling::match_interfaces(sides, 1e-9 * cut.size_m);
  }
}

coupling::StepPlan plan_steps(const LayerCut& cut, const std::vector<wire::Register>& regs,
                              bool common, std::int64_t lts_variable_tps) {
  std::vector<coupling::Tick> proposal;
  std::vector<double> elements;
  for (const auto& r : regs) {
    proposal.push_back(r.stable_step_ticks());
    elements.push_back(static_cast<double>(r.elements()));
  }
  std::vector<std::pair<int, int>> links;
  for (const auto& c : cut.interfaces) links.emplace_back(c.coarse, c.fine);
  if (lts_variable_tps > 0 && !common) {
    // the followers' proposals without the step safety, as their steppers send them: each
    // daemon's own_step_ticks (an older daemon's stable step in seconds, never below its
    // registered proposal)
    const coupling::TickClock clock(lts_variable_tps);
    std::vector<coupling::Tick> raw;
    for (const auto& r : regs) {
      if (r.own_step_ticks() > 0) {
        raw.push_back(r.own_step_ticks());
        continue;
      }
      const double s = r.stable_step_s();
      const coupling::Tick t = std::isfinite(s) && s > 0.0 && s < 1e3 ? clock.step_to_ticks(s) : 0;
      raw.push_back(r.stable_step_ticks() > 0 ? std::max(r.stable_step_ticks(), t) : 0);
    }
    proposal = coupling::lts_variable_first_proposals(proposal, raw, links, elements, cut.names);
  }
  return coupling::nested_steps(proposal, links, common, cut.names);
}

wire::Envelope setup_envelope(bool common, const std::string& scheme, const wire::Options& options,
                              std::int64_t ticks_per_second, coupling::Tick end_ticks) {
  wire::Envelope e;
  auto* s = e.mutable_setup();
  s->set_mode(common ? wire::MODE_SPLIT : wire::MODE_MULTI);
  s->set_scheme(scheme);
  *s->mutable_options() = options;
  s->set_ticks_per_second(ticks_per_second);
  s->set_end_time_ticks(end_ticks);
  return e;
}

wire::Envelope setup_message(const LayerCut& cut, const coupling::StepPlan& plan, int k,
                             bool common, const wire::Options& options,
                             std::int64_t ticks_per_second, const std::string& scheme) {
  // every domain ends at the same base instant (LayerStepper::set_end_time)
  wire::Envelope e = setup_envelope(common, scheme, options, ticks_per_second,
                                    coupling::aligned_end(plan, cut.end_time_s, ticks_per_second));
  auto* s = e.mutable_setup();
  s->set_step_ticks(plan.step[static_cast<std::size_t>(k)]);
  s->set_base_ticks(plan.base);
  for (const auto& c : cut.interfaces) {
    if (c.fine != k && c.coarse != k) continue;
    auto* li = s->add_layer_interfaces();
    const int partner = c.fine == k ? c.coarse : c.fine;
    li->set_index(c.index);
    li->set_partner(cut.names[static_cast<std::size_t>(partner)]);
    li->mutable_j_node_ids()->Add(c.j_node_ids.begin(), c.j_node_ids.end());
    li->set_fine_side(c.fine == k);
    li->set_partner_step_ticks(plan.step[static_cast<std::size_t>(partner)]);
  }
  return e;
}

}  // namespace crashlink::coordinator
