#include "solver/run/domain_timing.h"

#include <utility>

#include "solver/model/model.h"
#include "solver/run/peak_memory.h"

namespace crashlink::run {

io::DomainTiming domain_timing(const integration::Solver& solver, std::string name, double cpu_s,
                               std::int64_t elements, double setup_cpu_s) {
  io::DomainTiming d;
  d.name = std::move(name);
  d.cpu_seconds = cpu_s;
  d.cycles = solver.cycle();
  d.dt_min_s = solver.dt_min_s();
  d.elements = elements;
  d.threads = solver.threads();
  d.contact_seconds = solver.contact_cost().seconds;
  d.contact_node_cycles = solver.contact_cost().node_cycles;
  d.peak_rss_bytes = peak_resident_bytes();
  d.setup_cpu_seconds = setup_cpu_s;
  const auto kernels = solver.kernel_cost();
  const auto hex = static_cast<std::size_t>(model::ElementKind::Hex8);
  const auto shell = static_cast<std::size_t>(model::ElementKind::Shell4);
  d.kernel_sampled_cycles = kernels.sampled_cycles;
  d.hex_kernel_seconds = kernels.seconds[hex];
  d.hex_element_cycles = kernels.element_cycles[hex];
  d.shell_kernel_seconds = kernels.seconds[shell];
  d.shell_element_cycles = kernels.element_cycles[shell];
  d.global_step_seconds = kernels.global_step_seconds;
  return d;
}

}  // namespace crashlink::run
