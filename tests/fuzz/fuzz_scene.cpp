#include "tests/fuzz/fuzz_scene.h"

#include <google/protobuf/stubs/logging.h>

#include "solver/io/scenario_hash.h"
#include "solver/io/scenario_reader.h"

namespace crashlink::fuzz {

const std::string& scene_yaml() {
  static const std::string yaml = R"(name: fuzz_plate2
controls:
  end_time: 2.0e-5
materials:
  steel: {type: elastic, density: 7850.0, youngs_modulus: 2.1e+11, poisson_ratio: 0.3}
parts:
  fine:
    material: steel
    thickness: 1.0e-3
    mesh: {generator: plate, origin: [0.0, 0.0, 0.0], size: [0.02, 0.02], divisions: [4, 4]}
  coarse:
    material: steel
    thickness: 1.0e-3
    merge_nodes: true
    mesh: {generator: plate, origin: [0.02, 0.0, 0.0], size: [0.04, 0.02], divisions: [4, 2]}
node_sets:
  clamped: {box: {min: [0.0599, -1.0, -1.0], max: [0.1, 1.0, 1.0]}}
  loaded: {box: {min: [-1.0, -1.0, -1.0], max: [1.0e-4, 1.0, 1.0]}}
boundary:
  - {nodes: clamped, fix: all}
loads:
  - nodes: loaded
    dof: z
    curve: {t: [0.0, 1.0e-5, 2.0e-5], v: [0.0, 20.0, 0.0]}
domains:
  fine: {parts: [fine]}
  coarse: {parts: [coarse]}
)";
  return yaml;
}

const Scene& scene() {
  static const Scene s = [] {
    // Garbage strings make protobuf log "invalid UTF-8" on every parse: noise at 3000 inputs/s.
    google::protobuf::SetLogHandler(nullptr);
    Scene r;
    r.model = io::parse_scenario(scene_yaml(), "fuzz_plate2.yaml");
    r.dec = partition::decompose(r.model, partition::Scheme::Layer);
    r.cut = coordinator::layer_cut(r.model, r.dec);
    r.hash = io::scenario_hash_of_text(scene_yaml(), "fuzz_plate2.yaml");
    return r;
  }();
  return s;
}

}  // namespace crashlink::fuzz
