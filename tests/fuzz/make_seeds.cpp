// Seed corpus of the message fuzz targets (docs/fuzzing.md): `fuzz_make_seeds DIR` writes into
// DIR/coordinator/ and DIR/daemon/ the sessions of the small scene (fuzz_scene.h) as the
// processes exchange them, taken from two cosim::LayerSteppers driven against each other the way
// the coordinator routes their messages (split and multi steps), plus a few refused or broken
// sessions, and DIR/scenario/fuzz_plate2.yaml. Deterministic: rerunning rewrites the same bytes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "coordinator/layer_cut.h"
#include "coupling/ticks.h"
#include "proto/protocol_version.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_stepper.h"
#include "tests/fuzz/fuzz_frames.h"
#include "tests/fuzz/fuzz_scene.h"

namespace {

using namespace crashlink;
constexpr std::int64_t kTps = coupling::kDefaultTicksPerSecond;

std::string bytes(const wire::Envelope& e) {
  return e.SerializeAsString();
}

wire::Envelope hello(const std::string& domain, const std::string& hash, bool coordinator) {
  wire::Envelope e;
  auto* h = e.mutable_hello();
  h->set_protocol_version(wire::kProtocolVersion);
  h->set_scenario_hash(hash);
  h->set_domain(domain);
  h->set_role(coordinator ? wire::PEER_ROLE_COORDINATOR : wire::PEER_ROLE_DAEMON);
  if (coordinator) h->set_ticks_per_second(kTps);
  return e;
}

wire::Envelope envelope(const cosim::LayerMessage& m) {
  wire::Envelope e;
  if (m.kind == cosim::LayerMessage::Kind::Displacement) {
    auto* d = e.mutable_layer_displacement();
    d->set_interface_index(m.interface_index);
    d->set_time_ticks(m.time);
    d->mutable_displacements_m()->Add(m.first.begin(), m.first.end());
    d->mutable_angular_velocities_rad_s()->Add(m.second.begin(), m.second.end());
  } else {
    auto* f = e.mutable_layer_force();
    f->set_interface_index(m.interface_index);
    f->set_time_ticks(m.time);
    f->mutable_forces_n()->Add(m.first.begin(), m.first.end());
    f->mutable_moments_n_m()->Add(m.second.begin(), m.second.end());
  }
  return e;
}

void write(const std::filesystem::path& path, const std::string& data) {
  std::ofstream(path, std::ios::binary) << data;
  std::printf("%s (%zu bytes)\n", path.string().c_str(), data.size());
}

/// One run of both domains: the coordinator's input (every message, tagged by its sender) and
/// each daemon's input (Hello answer, Setup, the messages routed to it, a Bye).
struct Session {
  std::string coordinator;
  std::vector<std::string> daemon;
};

Session session(const fuzz::Scene& s, bool common, std::size_t max_messages) {
  const std::size_t n = s.cut.names.size();
  Session out;
  out.coordinator.assign(1, static_cast<char>(common ? 1 : 0));
  std::vector<cosim::LayerDomain> dom;
  std::vector<wire::Register> regs(n);
  for (std::size_t k = 0; k < n; ++k) {
    dom.push_back(cosim::build_layer_domain(s.dec, s.model, s.cut.names[k]));
    dom[k].solver->initialize();
    out.coordinator +=
        fuzz::frame(static_cast<std::uint8_t>(k), bytes(hello(s.cut.names[k], s.hash, false)));
  }
  for (std::size_t k = 0; k < n; ++k) {  // as Daemon::register_message, --step-safety 0.9
    const auto& sv = *dom[k].solver;
    auto& r = regs[k];
    r.set_stable_step_ticks(
        static_cast<std::int64_t>(std::floor(0.9 * sv.dt_s() * static_cast<double>(kTps))));
    r.set_stable_step_s(sv.dt_s());
    for (const auto& port : dom[k].ports) {
      auto* li = r.add_layer_interfaces();
      li->set_index(port.index);
      li->set_fine_side(port.fine_side);
      for (const auto l : port.local) {
        li->add_j_node_ids(sv.model().nodes.id[l]);
        li->add_masses_kg(port.fine_side ? 0.0 : sv.mass()[l]);
        for (std::size_t d = 0; d < 3; ++d) li->add_positions_m(sv.model().nodes.x0[3 * l + d]);
      }
    }
    wire::Envelope e;
    *e.mutable_registration() = r;
    out.coordinator += fuzz::frame(static_cast<std::uint8_t>(k), bytes(e));
  }
  const auto plan = coordinator::plan_steps(s.cut, regs, common);
  std::vector<cosim::LayerStepper> steppers;
  steppers.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto setup =
        coordinator::setup_message(s.cut, plan, static_cast<int>(k), common, {}, kTps);
    out.daemon.push_back(std::string(1, static_cast<char>(k)) +
                         fuzz::frame(0, bytes(hello("", s.hash, true))) +
                         fuzz::frame(0, bytes(setup)));
    for (auto& port : dom[k].ports)
      for (const auto& li : setup.setup().layer_interfaces())
        if (li.index() == port.index && port.fine_side) port.partner_step = li.partner_step_ticks();
    steppers.emplace_back(*dom[k].solver, std::move(dom[k].ports), setup.setup().step_ticks(),
                          kTps);
    steppers.back().initialize();
  }
  // Route as the coordinator does: each message to the other side of its interface.
  std::size_t sent = 0;
  for (bool moved = true; moved && sent < max_messages;) {
    moved = false;
    for (std::size_t k = 0; k < n; ++k) {
      if (steppers[k].advance() == cosim::LayerStepper::Wait::None) moved = true;
      for (const auto& m : steppers[k].take_outbox()) {
        moved = true;
        if (sent++ >= max_messages) break;
        const auto e = envelope(m);
        out.coordinator += fuzz::frame(static_cast<std::uint8_t>(k), bytes(e));
        for (std::size_t p = 0; p < n; ++p) {
          for (const auto& port : steppers[p].ports()) {
            if (p == k || port.index != m.interface_index) continue;
            out.daemon[p] += fuzz::frame(0, bytes(e));
            steppers[p].deliver(m);
          }
        }
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    wire::Envelope bye;
    bye.mutable_bye()->set_reason("end time reached");
    bye.mutable_bye()->mutable_report()->set_cycles(steppers[k].solver().cycle());
    out.coordinator += fuzz::frame(static_cast<std::uint8_t>(k), bytes(bye));
    wire::Envelope hb;
    hb.mutable_heartbeat()->set_sequence(7);
    out.daemon[k] += fuzz::frame(0, bytes(hb)) + fuzz::frame(0, bytes(bye));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR (tests/fuzz/corpus)\n");
    return 2;
  }
  const std::filesystem::path dir(argv[1]);
  for (const char* sub : {"coordinator", "daemon", "scenario"})
    std::filesystem::create_directories(dir / sub);
  const auto& s = fuzz::scene();
  for (bool common : {false, true}) {
    const std::string mode = common ? "split" : "multi";
    const auto full = session(s, common, 24);
    write(dir / "coordinator" / ("session_" + mode), full.coordinator);
    for (std::size_t k = 0; k < full.daemon.size(); ++k)
      write(dir / "daemon" / ("session_" + mode + "_" + s.cut.names[k]), full.daemon[k]);
  }
  // Refused and broken sessions: other version, other scenario, a stranger, garbage, an Error.
  auto wrong_version = hello(s.cut.names[0], s.hash, false);
  wrong_version.mutable_hello()->set_protocol_version(wire::kProtocolVersion + 1);
  auto wrong_hash = hello(s.cut.names[1], "0123456789abcdef", false);
  wire::Envelope error;
  error.mutable_error()->set_code(wire::ERROR_CODE_NUMERICAL);
  error.mutable_error()->set_message("blow-up");
  write(dir / "coordinator" / "refused",
        std::string(1, '\0') + fuzz::frame(0, bytes(wrong_version)) +
            fuzz::frame(1, bytes(wrong_hash)) +
            fuzz::frame(2, bytes(hello("stranger", s.hash, false))) +
            fuzz::frame(0, "\x0a\xff garbage") +
            fuzz::frame(0, bytes(hello(s.cut.names[0], s.hash, false))) +
            fuzz::frame(0, bytes(error)));
  write(dir / "daemon" / "refused", std::string(1, '\0') + fuzz::frame(0, bytes(error)));
  write(dir / "scenario" / "fuzz_plate2.yaml", fuzz::scene_yaml());
  return 0;
}
