// libFuzzer target: what crashlink-solver does with the coordinator's messages (docs/fuzzing.md).
// Input: fuzz_frames.h; the flags byte's bit 0 picks the domain (the small scene of
// fuzz_scene.h: 0 fine, 1 coarse); every frame is one message from the coordinator, in order:
//   the answer to the Hello (DaemonLink's constructor: garbage or anything but a coordinator
//   Hello is a ProtocolError, an Error a RemoteError; then the daemon refuses a tick < 1),
//   then DaemonLink::receive's rules (garbage, a second Hello: ProtocolError; an Error:
//   RemoteError; Heartbeats swallowed), the Setup (daemon.cpp await_setup, then
//   daemon::apply_setup, the LayerStepper built with its step and initialize()), then the run:
//   each message through layer_wire's to_layer_message and LayerStepper::deliver (daemon.cpp
//   deliver(): a Bye or another message is a ProtocolError, the stepper's ModelError becomes
//   one), after which the stepper advances as far as it can on a real solver.
// Work per input is bounded the way the simulated time bounds a run: after kMaxCycles cycles the
// input is done (a valid Setup may ask for many tiny steps; that is a long run, not a bug). A
// frame's tag does not matter.
// Expected failures, which end the daemon as it ends: ProtocolError,
// transport::RemoteError, ModelError (stepper set-up, step above the stable one), NumericalError
// (the guard, e.g. after absurd ghost displacements). Anything else escapes and is a bug.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <zmq.hpp>

#include "core/errors.h"
#include "solver/cosim/layer_domains.h"
#include "solver/cosim/layer_stepper.h"
#include "solver/daemon/apply_setup.h"
#include "solver/daemon/layer_wire.h"
#include "tests/fuzz/fuzz_frames.h"
#include "tests/fuzz/fuzz_scene.h"
#include "tests/fuzz/fuzz_verbose.h"
#include "transport/detail/zmq.h"
#include "transport/errors.h"

namespace {

using namespace crashlink;

constexpr std::int64_t kMaxCycles = 400;

/// The input's work bound was reached.
struct Enough {};

/// DaemonLink's reading of one message from the coordinator (receive(), after the handshake).
std::optional<wire::Envelope> receive(std::span<const std::uint8_t> bytes) {
  zmq::message_t message(bytes.data(), bytes.size());
  wire::Envelope e;
  if (const auto error = transport::detail::parse(message, e); !error.empty())
    throw ProtocolError("coordinator", error);
  switch (e.body_case()) {
    case wire::Envelope::kHeartbeat:
      return std::nullopt;
    case wire::Envelope::kError:
      throw transport::RemoteError(e.error());
    case wire::Envelope::kHello:
      throw ProtocolError("coordinator", "a second Hello");
    default:
      return e;
  }
}

void run(const fuzz::Scene& scene, const std::string& domain, fuzz::FrameReader& in) {
  auto dom = cosim::build_layer_domain(scene.dec, scene.model, domain);
  dom.solver->initialize();
  // The answer to the Hello (DaemonLink's constructor, then Daemon::connect()).
  auto first = in.next();
  if (!first) return;
  zmq::message_t message(first->bytes.data(), first->bytes.size());
  wire::Envelope hello;
  if (const auto error = transport::detail::parse(message, hello); !error.empty())
    throw ProtocolError("coordinator", error);
  if (hello.has_error()) throw transport::RemoteError(hello.error());
  if (!hello.has_hello() || hello.hello().role() != wire::PEER_ROLE_COORDINATOR)
    throw ProtocolError("coordinator", "not a coordinator Hello");
  const std::int64_t tps = hello.hello().ticks_per_second();
  if (tps < 1) throw ProtocolError("coordinator", "ticks per second < 1");
  // await_setup(): the next message that is not a Heartbeat must be the Setup.
  std::optional<wire::Envelope> setup;
  while (!setup) {
    auto f = in.next();
    if (!f) return;
    setup = receive(f->bytes);
  }
  if (!setup->has_setup()) throw ProtocolError("coordinator", "not a Setup");
  daemon::apply_setup(setup->setup(), tps, domain, dom.ports);
  cosim::LayerStepper stepper(*dom.solver, std::move(dom.ports), setup->setup().step_ticks(), tps);
  stepper.initialize();
  std::int64_t cycles = 0;
  const auto on_sample = [&] {
    if (++cycles > kMaxCycles) throw Enough();
  };
  if (stepper.advance(on_sample) == cosim::LayerStepper::Wait::Finished) return;
  (void)stepper.take_outbox();
  while (auto f = in.next()) {
    auto e = receive(f->bytes);
    if (!e) continue;
    auto m = daemon::to_layer_message(*e);
    if (!m) throw ProtocolError("coordinator", "a Bye or another message in the run");
    try {
      stepper.deliver(*m);
    } catch (const ModelError& x) {
      throw ProtocolError("coordinator", x.what());
    }
    if (stepper.advance(on_sample) == cosim::LayerStepper::Wait::Finished) return;
    (void)stepper.take_outbox();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& scene = fuzz::scene();
  fuzz::FrameReader in(data, size);
  const std::string& domain = scene.cut.names[in.flags() % scene.cut.names.size()];
  try {
    run(scene, domain, in);
  } catch (const Enough&) {
  } catch (const ProtocolError& e) {
    fuzz::report(e);
  } catch (const transport::RemoteError& e) {
    fuzz::report(e);
  } catch (const ModelError& e) {
    fuzz::report(e);
  } catch (const NumericalError& e) {
    fuzz::report(e);
  }
  return 0;
}
