#pragma once
// Helpers for tests of cosim::LayerNetwork: its checkpoint files, and the lts energy's drift.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/state_archive.h"
#include "solver/cosim/layer_network.h"

namespace crashlink::testing {

/// `multi` under the lts coupling: each domain at its own fixed step, `safety` of its stable one.
inline cosim::LayerNetworkOptions lts_multi(double safety = 0.9) {
  cosim::LayerNetworkOptions o;
  o.run.scheme = "lts";
  o.run.common_step = false;
  o.step_safety = safety;
  return o;
}

/// Every domain's checkpoint (LayerNetwork::save_state) into dir/<domain>.bin, dir created;
/// returns the paths in domain order, for LayerNetwork::restore.
inline std::vector<std::string> save_network(const cosim::LayerNetwork& net,
                                             const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> paths;
  for (std::size_t k = 0; k < net.size(); ++k) {
    core::StateWriter w;
    net.save_state(k, w);
    paths.push_back((dir / (net.solver(k).domain_name() + ".bin")).string());
    w.save(paths.back());
  }
  return paths;
}

/// How many values of two runs' displacements (global_displacement) differ in any bit; the
/// sizes must agree (else SIZE_MAX).
inline std::size_t differing(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return static_cast<std::size_t>(-1);
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

struct EnergyDrift {
  std::int64_t samples = 0;  ///< coarse instants with a finite summed E
  double drift = 0.0;        ///< max |E / E0 - 1| over them
};

/// Runs `net` (initialised) to its end, and sums the domains' lts shares (lts_energy_J) at each
/// instant of the plan's base once every domain has sampled it (the last of them to begin
/// that cycle; no domain has passed the next base instant then).
inline EnergyDrift run_summed_energy_drift(cosim::LayerNetwork& net) {
  EnergyDrift r;
  double e0 = 0.0;
  std::size_t count = 0;
  const auto base = net.plan().base;
  net.run([&](std::size_t k) {
    if (net.stepper(k).time() % base != 0) return;
    if (++count < net.size()) return;
    count = 0;
    const double E = net.lts_energy_J();
    if (!std::isfinite(E)) return;
    if (r.samples++ == 0) e0 = E;
    r.drift = std::max(r.drift, std::abs(E / e0 - 1.0));
  });
  return r;
}

}  // namespace crashlink::testing
