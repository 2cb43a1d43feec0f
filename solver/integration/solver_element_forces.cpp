// The solver's element forces (solver.h): the kernels per part over the threads' chunks, their
// results folded in chunk order, and the sampled cost per element kind.
#include <algorithm>
#include <limits>

#include "core/cpu_clock.h"
#include "core/errors.h"
#include "solver/integration/solver.h"

namespace crashlink::integration {

void Solver::compute_forces(double dt, ElementSpan span) {
  if (span != ElementSpan::Rim) {
    on_node_ranges([&](std::size_t i0, std::size_t i1) {
      std::fill(f_int_.begin() + static_cast<std::ptrdiff_t>(3 * i0),
                f_int_.begin() + static_cast<std::ptrdiff_t>(3 * i1), 0.0);
      for (std::size_t b = i0; b < i1; b += kNodeTile)  // zero and left so off the turning tiles
        if (turning(b))
          std::fill(m_int_.begin() + static_cast<std::ptrdiff_t>(3 * b),
                    m_int_.begin() + static_cast<std::ptrdiff_t>(3 * std::min(i1, b + kNodeTile)),
                    0.0);
    });
    dt_stable_ = std::numeric_limits<double>::infinity();
    for (auto& rt : parts_) rt.last = {};
    global_.ratio = std::numeric_limits<double>::infinity();
    global_.ratio_element = -1;
  }
  if (span == ElementSpan::All) {  // the initial call: every part in one call, on this thread
    for (std::size_t p = 0; p < parts_.size(); ++p)
      add_kernel_result(p, run_kernel(p, dt, 0, model_.parts[p].element_count(), nullptr));
    return;
  }
  const int s = span == ElementSpan::Interior ? 0 : 1;
  const auto& chunks = chunks_.chunks(s);
  if (chunks.empty()) return;  // a span without elements (mono's rim): no loop to wake for
  run_span(s, dt, false, f_int_.data(), m_int_.data());
  for (std::size_t k = 0; k < chunks.size(); ++k)
    add_kernel_result(chunks[k].part, chunk_results_[k]);
  if (global_.on) {  // the smallest element ratio of the span, the first on a tie
    for (std::size_t k = 0; k < chunks.size(); ++k)
      if (global_.chunk_ratio[k] < global_.ratio) {
        global_.ratio = global_.chunk_ratio[k];
        global_.ratio_part = chunks[k].part;
        global_.ratio_element = global_.chunk_element[k];
      }
  }
}

void Solver::run_span(int s, double dt, bool probe, double* f, double* m) {
  // The span's chunks, each thread its block of them, each chunk into its own result; then the
  // shared nodes' slots (ElementChunks); then the results folded in chunk order by the caller:
  // the same bits for any team size.
  const auto& chunks = chunks_.chunks(s);
  for (const auto& c : chunks) prepare_element_steps(c.part);
  const bool ratio = global_.on && !probe;
  const bool rate_terms = s == 0 || ghost_bulk_viscosity_;  // set_ghost_bulk_viscosity
  // kernel_cost(): the sampled cycles, and every probe (slot 2)
  const bool timed = probe || cycle_ % kKernelSampleCycles == kKernelSampleCycles - 1;
  const auto kind = [&](std::size_t p) {
    return probe ? std::size_t{2} : static_cast<std::size_t>(model_.parts[p].kind);
  };
  const auto run_chunks = [&](std::size_t k0, std::size_t k1, std::array<double, 3>& cpu_s) {
    // Timed calls read this thread's clock where the element kind changes (the chunks are in
    // part order), so a few reads per span, not one per chunk.
    double c0 = timed && k0 < k1 ? core::thread_cpu_seconds() : 0.0;
    for (std::size_t k = k0; k < k1; ++k) {
      const auto& c = chunks[k];
      if (timed && k > k0 && kind(c.part) != kind(chunks[k - 1].part)) {
        const double c1 = core::thread_cpu_seconds();
        cpu_s[kind(chunks[k - 1].part)] += c1 - c0;
        c0 = c1;
      }
      chunks_.clear_slots(c);
      chunk_results_[k] = run_kernel(c.part, dt, c.first, c.end, chunks_.scatter(c.part), probe,
                                     rate_terms, s == 1 && !probe);
      if (ratio)
        global_.chunk_ratio[k] = element_ratio(c.part, c.first, c.end, global_.chunk_element[k]);
    }
    if (timed && k0 < k1) cpu_s[kind(chunks[k1 - 1].part)] += core::thread_cpu_seconds() - c0;
  };
  if (chunks.empty()) return;
  if (timed && !probe) {
    for (const auto& c : chunks)
      kernel_element_cycles_[kind(c.part)] += static_cast<std::int64_t>(c.end - c.first);
    if (cycle_ != kernel_last_sampled_) {  // a cycle's two spans (interior, rim) count once
      kernel_last_sampled_ = cycle_;
      ++kernel_sampled_cycles_;
    }
  }
  if (team_) {
    const auto& cut = chunk_cut_[s];
    team_->on_each_thread([&](int t) {
      run_chunks(cut[t], cut[t + 1], kernel_worker_cpu_[static_cast<std::size_t>(t)]);
    });
    const std::size_t shared = chunks_.shared_nodes(s);
    const auto parts = static_cast<std::size_t>(team_->size());
    if (shared > 0)
      team_->on_each_thread([&](int t) {
        const auto k = static_cast<std::size_t>(t);
        chunks_.replay(s, shared * k / parts, shared * (k + 1) / parts, f, m);
      });
  } else {
    run_chunks(0, chunks.size(), kernel_worker_cpu_[0]);
  }
}

Solver::KernelCost Solver::kernel_cost() const {
  KernelCost c;
  c.sampled_cycles = kernel_sampled_cycles_;
  c.element_cycles = kernel_element_cycles_;
  for (const auto& t : kernel_worker_cpu_)
    for (std::size_t k = 0; k < 2; ++k) c.seconds[k] += t[k];
  // The calling thread's probes are in its own refresh time; the workers' are added.
  c.global_step_seconds = global_step_cpu_s_;
  for (std::size_t t = 1; t < kernel_worker_cpu_.size(); ++t)
    c.global_step_seconds += kernel_worker_cpu_[t][2];
  return c;
}

void Solver::prepare_element_steps(std::size_t p) {
  auto& rt = parts_[p];
  const std::size_t ne = model_.parts[p].element_count();
  if (record_element_steps_ && rt.element_dt_s.size() != ne) rt.element_dt_s.assign(ne, 0.0);
}

elements::KernelResult Solver::run_kernel(std::size_t p, double dt, std::size_t first,
                                          std::size_t end, const std::int32_t* scatter, bool probe,
                                          bool rate_terms, bool rim) {
  const auto& part = model_.parts[p];
  auto& rt = parts_[p];
  const auto& mat = model_.materials[static_cast<std::size_t>(part.material)];
  const auto& c = model_.controls;
  // probe: the global step's product K y (refresh_global_step), on zero-stress histories
  const elements::NodalView nv =
      probe ? elements::NodalView{x_.data(),        global_.v.data(), global_.w.data(),
                                  global_.f.data(), global_.m.data(), chunks_.f_slots(),
                                  chunks_.m_slots()}
            : elements::NodalView{x_.data(),     v_.data(),         omega_.data(),    f_int_.data(),
                                  m_int_.data(), chunks_.f_slots(), chunks_.m_slots()};
  auto& state = probe ? global_.probe_states[p] : rt.state;
  elements::StepInfo step{dt, c.bulk_viscosity && !probe && rate_terms, c.bulk_q_linear,
                          c.bulk_q_quadratic, c.bulk_linear_in_expansion};
  step.first_element = first;
  step.end_element = end;
  step.scatter = scatter;
  if (rim) {
    step.trial_history = rim_trial_history_;
    step.defer_return = rim_defer_return_;
  }
  if (probe) {
    step.element_dt_s = global_.probe_dt[p].data();
  } else if (record_element_steps_ && !std::holds_alternative<std::monostate>(rt.state)) {
    prepare_element_steps(p);
    step.element_dt_s = rt.element_dt_s.data();
  }
  if (first >= std::min(end, part.element_count())) return {};
  if (auto* hs = std::get_if<elements::Hex8State>(&state))
    return elements::hex8_internal_forces(part, mat, *hs, nv, step);
  if (auto* ss = std::get_if<elements::ShellState>(&state)) {
    step.bulk_viscosity = step.bulk_viscosity && c.shell_bulk_viscosity;
    return elements::shell_internal_forces(part, mat, *ss, nv, step);
  }
  return {};
}

void Solver::add_kernel_result(std::size_t p, const elements::KernelResult& r) {
  auto& rt = parts_[p];
  rt.internal_energy_J += r.internal_energy_increment_J;
  rt.hourglass_energy_J += r.hourglass_energy_increment_J;
  rt.damping_energy_J += r.damping_energy_increment_J;  // included in internal
  energy_.internal_J += r.internal_energy_increment_J;
  energy_.hourglass_J += r.hourglass_energy_increment_J;
  // the part's calls of this cycle: energies summed, the smallest step (the first on a tie)
  rt.last.internal_energy_increment_J += r.internal_energy_increment_J;
  rt.last.hourglass_energy_increment_J += r.hourglass_energy_increment_J;
  rt.last.damping_energy_increment_J += r.damping_energy_increment_J;
  if (r.dt_stable_s < rt.last.dt_stable_s) {
    rt.last.dt_stable_s = r.dt_stable_s;
    rt.last.critical_element = r.critical_element;
  }
  if (r.dt_stable_s < dt_stable_) {
    dt_stable_ = r.dt_stable_s;
    critical_part_ = p;
    critical_local_ = r.critical_element;
  }
}

}  // namespace crashlink::integration
