#pragma once
// A coupling scheme as the coordinator sees it (docs/design.md §2.6, §2.7): the scheme's cut of the
// scenario, its check of each Register, its plan and Setups, and what it does with each message
// of the run (route a layer vector, answer a free state, record the interface history). It does no
// IO of its own: the coordinator (coordinator_run.cpp), a message pump around it, admits the
// daemons, hands their messages over, handles Bye, Error, silence and stop, and owns the files
// (the interface histories, the checkpoints) that the scheme fills through its CoordinatorPort.
// Implemented by `layer` (layer_coordinator_scheme.h) and `paper` (paper_coordinator_scheme.h);
// listed by name in coordinator_schemes.h.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "coordinator/coordinator_run.h"
#include "coordinator/layer_cut.h"
#include "coupling/ticks.h"
#include "proto/crashlink.pb.h"

namespace crashlink::coordinator {

class CouplingHistory;
class CoordinatorCheckpoints;

/// What a scheme may ask of the coordinator process.
class CoordinatorPort {
 public:
  /// To domain k (its index in the cut).
  virtual void send(int k, const wire::Envelope& e) = 0;
  /// The message being handled, its bytes as they came, to domain `to` (dropped if it finished).
  virtual void forward_current(int to) = 0;
  /// Domain k is at its end time and writes its results: a longer silence is allowed.
  virtual void allow_silence(int k) = 0;
  /// DIR/coordinator.h5's interface histories.
  virtual CouplingHistory& history() = 0;
  /// The run's checkpoints (DIR/checkpoints, docs/checkpoints.md): the scheme plans the interval
  /// from its steps, resumes a restart and says when its state is complete at an instant; the
  /// coordinator owns them and prunes them at the end.
  virtual CoordinatorCheckpoints& checkpoints() = 0;
  /// The run's CPU time so far (with the runs before a restart), s.
  virtual double cpu_seconds() const = 0;
  /// One line on the coordinator's log.
  virtual void log(const std::string& line) = 0;

 protected:
  ~CoordinatorPort() = default;
};

class CoordinatorScheme {
 public:
  virtual ~CoordinatorScheme() = default;

  /// The domains (cut order: a daemon's index k), the interfaces, the end time.
  virtual const LayerCut& cut() const = 0;
  /// Daemon k's Register against the cut. Throws ModelError naming the domain and the values.
  virtual void check_register(int k, const wire::Register& r) const = 0;
  /// Every domain registered: matches the interfaces (coupling::InterfaceError naming the
  /// domains), plans the steps, resumes a restart, sends every Setup and logs the plan.
  virtual void start(const std::vector<wire::Register>& regs, const wire::Options& options,
                     CoordinatorPort& port) = 0;
  /// A message from domain k during the run. false: not one of this scheme's (the coordinator
  /// deals with it). Throws ProtocolError for one out of its turn.
  virtual bool receive(int k, const wire::Envelope& e, CoordinatorPort& port) = 0;
  /// Domain k said Bye. Throws ProtocolError when it may not yet.
  virtual void bye(int k, const wire::Bye& b, CoordinatorPort& port) = 0;
  /// The instant domain k reported last, ticks.
  virtual coupling::Tick reached(int k) const = 0;
  /// Domain k's planned step, ticks (0 before start()).
  virtual coupling::Tick step(int k) const = 0;
  /// The scheme's figures in the result (routed vectors, lanes, reports; the coordinator fills
  /// the checkpoints' own).
  virtual void fill_result(CoordinatorResult& r) const = 0;
  /// The CPU time of the runs before the checkpoint resumed from, s.
  virtual double cpu_before() const = 0;
};

}  // namespace crashlink::coordinator
