#pragma once
// The `layer` network at a fixed common step against one Solver at that step (split = mono to
// round-off, docs/design.md §2.7): used by the split tests of YAML scenes and of keyword decks.
#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/cosim/layer_network.h"
#include "solver/integration/solver.h"

namespace crashlink::testing {

struct NetworkVsMono {
  double rel_diff = 1.0;  ///< max |u_network - u_mono| / max |u_mono| over every global dof
  double u_scale = 0.0;   ///< max |u_mono| [m]
  double total_J = 0.0, mono_total_J = 0.0;  ///< energies at the end
  double step_s = 0.0;                       ///< the common step
};

/// Runs `global` as cosim::LayerNetwork at its common step (safety 0.9) and as one Solver at
/// that step for `cycles` steps (cycles <= 0: as many as fit in the end time, less one).
inline NetworkVsMono network_vs_mono(const model::Model& global, int cycles) {
  cosim::LayerNetworkOptions o;
  o.run.common_step = true;
  o.step_safety = 0.9;  // a fixed step: margin for the step's shrinking under load
  cosim::LayerNetwork net(global, o);
  net.initialize();
  const coupling::Tick h = net.plan().step[0];
  NetworkVsMono r;
  r.step_s = net.seconds(h);
  if (cycles <= 0) cycles = static_cast<int>(global.controls.end_time_s / r.step_s) - 1;
  integration::Solver mono(global, "mono");
  mono.initialize();
  mono.impose_step(r.step_s);
  for (int n = 0; n < cycles; ++n) {
    mono.begin_cycle();
    mono.end_cycle();
    mono.impose_step(r.step_s);
  }
  mono.begin_cycle();
  // Every domain samples t = cycles h after its begin_cycle() (energies complete there) and
  // pauses at the start of the next cycle.
  const coupling::Tick t_end = h * cycles;
  const auto& d = net.domains();
  std::vector<double> u(3 * global.nodes.count(), 0.0);
  net.run(
      [&](std::size_t k) {
        if (net.stepper(k).time() != t_end) return;
        const auto& s = net.solver(k);
        r.total_J += s.energy().total_J();
        for (std::size_t g = 0; g < d.owner_solver.size(); ++g)
          if (d.owner_solver[g] == k)
            for (std::size_t c = 0; c < 3; ++c)
              u[3 * g + c] = s.displacement()[3 * d.owner_local[g] + c];
      },
      t_end + 1);
  const auto& um = mono.displacement();
  double worst = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    r.u_scale = std::max(r.u_scale, std::abs(um[i]));
    worst = std::max(worst, std::abs(u[i] - um[i]));
  }
  r.mono_total_J = mono.energy().total_J();
  r.rel_diff = r.u_scale > 0.0 ? worst / r.u_scale : 1.0;
  return r;
}

}  // namespace crashlink::testing
