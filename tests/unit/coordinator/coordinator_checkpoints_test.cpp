// coordinator::CoordinatorCheckpoints (coordinator_checkpoints.h): the coordinator writes its
// checkpoint at an instant once a daemon has announced it and every interface's history rows have
// reached it, once per instant although every daemon announces it; a restart resumes the router
// and the histories there and does not write that instant again.
#include "coordinator/coordinator_checkpoints.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/run/checkpoint_store.h"

using namespace crashlink;
using coupling::Tick;

namespace {

struct Fixture {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("crashlink_coordinator_checkpoints_" + std::to_string(::getpid()));
  coordinator::LayerCut cut;
  coordinator::CoordinatorOptions o;
  Fixture() {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    cut.names = {"fine", "coarse"};
    cut.domain_index = {0, 1};
    coordinator::CutInterface c;
    c.fine = 0;
    c.coarse = 1;
    c.j_node_ids = {1, 2};
    c.kind = "link";
    c.name = "fine-coarse";
    cut.interfaces.push_back(c);
    o.out_dir = dir.string();
    o.log = nullptr;
    o.run.ticks_per_second = 10;  // H = 1 tick: the interval of 0.4 s is 4 ticks
    o.run.checkpoint_interval_s = 0.4;
    o.run.variable_steps = true;
  }
  ~Fixture() { std::filesystem::remove_all(dir); }
  coupling::LayerRouter router() const {
    coupling::LayerRouter r({{0, 1, 2, 1, 0.1}}, cut.names);
    r.set_variable_steps(true);
    return r;
  }
  std::vector<coupling::LayerSample> rows(std::vector<Tick> times) const {
    std::vector<coupling::LayerSample> out(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) out[i].time = times[i];
    return out;
  }
};

}  // namespace

TEST(CoordinatorCheckpoints, WritesEachAnnouncedInstantOnceWhenTheRowsHaveReachedIt) {
  Fixture f;
  auto router = f.router();
  coordinator::CouplingHistory history((f.dir / "coordinator.h5").string(), f.cut);
  coordinator::CoordinatorCheckpoints ck(f.o, f.cut, "hash");
  ASSERT_EQ(ck.plan({1, 1}), 4);

  ck.announced(5);  // the leader's first instant after 4 ticks, from the coarse daemon
  ck.write_when_complete(router, history, 1.0);
  EXPECT_EQ(ck.written(), 0) << "written before the fine side's rows reached it";
  history.append(0, f.rows({0, 2, 5}), f.o.run.ticks_per_second);
  ck.rows_reached(0, 5);
  ck.write_when_complete(router, history, 1.0);
  EXPECT_EQ(ck.written(), 1);
  ck.announced(5);  // the fine daemon's announcement, later
  ck.write_when_complete(router, history, 2.0);
  EXPECT_EQ(ck.written(), 1) << "the same instant written twice";
  EXPECT_EQ(run::list_checkpoints(f.dir.string(), "coordinator"), std::vector<std::int64_t>{5});

  // a restart from 5 expects rows after 5, and does not write 5 again
  coordinator::CouplingHistory again((f.dir / "coordinator2.h5").string(), f.cut);
  auto router2 = f.router();
  coordinator::CoordinatorCheckpoints restarted(f.o, f.cut, "hash");
  restarted.plan({1, 1});
  EXPECT_EQ(restarted.restore(5, router2, again), 1.0);  // the CPU before the checkpoint
  EXPECT_EQ(restarted.restarted_from(), 5);
  restarted.announced(5);
  restarted.write_when_complete(router2, again, 3.0);
  EXPECT_EQ(restarted.written(), 0);
  coordinator::CoordinatorCheckpoints other(f.o, f.cut, "another scenario");
  EXPECT_THROW(other.restore(5, router2, again), CheckpointError);
}
