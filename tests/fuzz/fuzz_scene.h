#pragma once
// The small two-domain scene the message fuzz targets run against (fuzz_scene.cpp): a 1 mm steel
// shell plate of two parts merged on x = 0.02 m, "fine" (5 mm elements) and "coarse" (10 mm),
// domains fine / coarse, so the `layer` cut has one interface whose J nodes rotate (moments and
// angular velocities are exercised). Built once per process.
#include <cstdint>
#include <string>

#include "coordinator/layer_cut.h"
#include "solver/model/model.h"
#include "solver/partition/decomposition.h"

namespace crashlink::fuzz {

struct Scene {
  model::Model model;
  partition::Decomposition dec;
  coordinator::LayerCut cut;
  std::string hash;  ///< the scenario hash the daemons' Hellos must carry
};

/// The scenario text (YAML).
const std::string& scene_yaml();

/// The scene, parsed and cut once (the first call also silences protobuf's log).
const Scene& scene();

}  // namespace crashlink::fuzz
