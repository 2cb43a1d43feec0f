// libFuzzer target: what crashlink-coordinator does with the messages of its daemons
// (docs/fuzzing.md). Input: fuzz_frames.h; the flags byte's bit 0 picks split (1) or multi (0)
// steps; each frame's tag picks the sender (tag % 3: the scene's domain 0 or 1, or a stranger).
// Every frame goes the way a message goes in the coordinator, against its own cut of the small
// scene of fuzz_scene.h:
//   bytes -> transport::detail::parse (CoordinatorLink::handle: garbage is refused, the run goes
//   on) -> a Hello checked by transport::check_hello (refused: the run goes on; a second Hello in
//   a session: refused); nothing before an accepted Hello; Heartbeats swallowed ->
//   admission (coordinator_run.cpp admit()): an Error stops the run, anything but one Register is
//   a protocol stop, coordinator::check_register; once all registered: match_sides,
//   plan_steps, the LayerRouter and every Setup ->
//   routing (route()): LayerForce / LayerDisplacement through LayerRouter::force /
//   displacement (the forward target must be a known domain; a finished one gets nothing), Bye,
//   Error, anything else a protocol stop.
// The coupling history file (CouplingHistory, HDF5) is not written: file I/O per input would
// cost more than it finds; the rows LayerRouter returns are checked instead (finite time order).
// Expected failures, which end the run as the coordinator ends it: ProtocolError,
// ModelError (check_register, match_sides' InterfaceError, nested_steps). Anything else escapes
// and is a bug.
#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "coordinator/layer_cut.h"
#include "core/errors.h"
#include "coupling/layer_router.h"
#include "tests/fuzz/fuzz_frames.h"
#include "tests/fuzz/fuzz_scene.h"
#include "tests/fuzz/fuzz_verbose.h"
#include "transport/detail/zmq.h"
#include "transport/session.h"

namespace {

using namespace crashlink;

std::span<const double> view(const google::protobuf::RepeatedField<double>& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

/// The run ended (a protocol stop, a remote Error, every daemon said Bye): why.
struct RunOver : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Coordinator {
 public:
  Coordinator(const coordinator::LayerCut& cut, const std::string& hash, bool common)
      : cut_(cut), hash_(hash), common_(common) {
    regs_.resize(cut_.names.size());
    registered_.assign(cut_.names.size(), false);
    finished_.assign(cut_.names.size(), false);
  }

  /// One ZeroMQ message from routing id `id`.
  void receive(const std::string& id, std::span<const std::uint8_t> bytes) {
    zmq::message_t message(bytes.data(), bytes.size());
    wire::Envelope e;
    if (!transport::detail::parse(message, e).empty()) return;  // refused, logged
    auto peer = active_.find(id);
    if (e.has_hello()) {
      if (peer != active_.end() && peer->second) return;                 // second Hello: refused
      if (transport::check_hello(e.hello(), hash_, cut_.names)) return;  // refused
      // The harness names each connection by its domain (CoordinatorLink maps the two).
      if (e.hello().domain() != id) return;
      active_[id] = true;
      return;
    }
    if (peer == active_.end() || !peer->second) return;  // before its Hello: dropped
    if (e.has_heartbeat()) return;
    if (e.has_error() || e.has_bye()) peer->second = false;
    const int k = index_of(id);
    if (k < 0) std::abort();  // check_hello admits known domains only
    if (!router_) {
      admit(k, e);
    } else {
      route(k, e);
    }
  }

 private:
  int index_of(const std::string& domain) const {
    for (std::size_t k = 0; k < cut_.names.size(); ++k)
      if (cut_.names[k] == domain) return static_cast<int>(k);
    return -1;
  }

  void admit(int k, const wire::Envelope& e) {
    const auto ku = static_cast<std::size_t>(k);
    if (e.has_error()) throw RunOver("a daemon's Error before the Setups");
    if (!e.has_registration() || registered_[ku]) throw RunOver("protocol stop: not one Register");
    coordinator::check_register(cut_, k, e.registration());
    regs_[ku] = e.registration();
    registered_[ku] = true;
    for (bool r : registered_)
      if (!r) return;
    coordinator::match_sides(cut_, regs_);
    const auto plan = coordinator::plan_steps(cut_, regs_, common_);
    std::vector<coupling::LayerRoute> routes;
    for (const auto& c : cut_.interfaces) {
      const auto H = plan.step[static_cast<std::size_t>(c.coarse)];
      if (H < 1) std::abort();  // nested_steps promises steps >= 1
      routes.push_back({c.fine, c.coarse, c.j_node_ids.size(), H,
                        static_cast<double>(H) / static_cast<double>(kTicksPerSecond)});
    }
    router_ = std::make_unique<coupling::LayerRouter>(std::move(routes), cut_.names);
    wire::Options options;
    for (std::size_t d = 0; d < cut_.names.size(); ++d) {
      const auto s = coordinator::setup_message(cut_, plan, static_cast<int>(d), common_, options,
                                                kTicksPerSecond);
      if (s.setup().step_ticks() < 1) std::abort();
    }
  }

  void route(int k, const wire::Envelope& e) {
    try {
      if (e.has_layer_report()) {
        for (const auto& rows : e.layer_report().rows()) {
          const auto samples = router_->rows(
              k, rows.interface_index(),
              {rows.time_ticks().data(), static_cast<std::size_t>(rows.time_ticks_size())},
              view(rows.force_n()), view(rows.link_work_j()));
          for (std::size_t i = 1; i < samples.size(); ++i)
            if (samples[i].time <= samples[i - 1].time) std::abort();
        }
      } else if (e.has_layer_force()) {
        const auto& f = e.layer_force();
        check(router_->force(k, f.interface_index(), f.time_ticks(), view(f.forces_n()),
                             view(f.moments_n_m())));
      } else if (e.has_layer_displacement()) {
        const auto& d = e.layer_displacement();
        check(router_->displacement(k, d.interface_index(), d.time_ticks(),
                                    view(d.displacements_m()), view(d.angular_velocities_rad_s())));
      } else if (e.has_bye()) {
        finished_[static_cast<std::size_t>(k)] = true;
        for (bool f : finished_)
          if (!f) return;
        throw RunOver("every daemon said Bye");
      } else {
        throw RunOver("an Error, or a protocol stop: another message during the run");
      }
    } catch (const ProtocolError& x) {
      throw RunOver(std::string("protocol stop: ") + x.what());
    }
  }

  void check(const coupling::LayerRouter::Routed& r) const {
    if (r.to < 0 || static_cast<std::size_t>(r.to) >= cut_.names.size()) std::abort();
  }

  static constexpr std::int64_t kTicksPerSecond = coupling::kDefaultTicksPerSecond;
  const coordinator::LayerCut& cut_;
  const std::string& hash_;
  bool common_;
  std::map<std::string, bool> active_;  ///< routing id -> in session
  std::vector<wire::Register> regs_;
  std::vector<bool> registered_, finished_;
  std::unique_ptr<coupling::LayerRouter> router_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& scene = fuzz::scene();
  fuzz::FrameReader in(data, size);
  Coordinator c(scene.cut, scene.hash, (in.flags() & 1) != 0);
  const std::size_t n = scene.cut.names.size();
  try {
    while (auto f = in.next()) {
      const std::size_t k = f->tag % (n + 1);
      c.receive(k < n ? scene.cut.names[k] : std::string("stranger"), f->bytes);
    }
  } catch (const RunOver& e) {
    fuzz::report(e);
  } catch (const ModelError& e) {  // check_register, match_sides, nested_steps: the run stops
    fuzz::report(e);
  }
  return 0;
}
