// Shared-memory lanes (transport/shm_queue.h, shm_lane.h): the ring keeps whole messages in order
// across its wrap-around, refuses what cannot fit, reports a reader that does not read, wakes a
// sleeping reader, and carries messages between two processes.
#include "transport/shm_lane.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "transport/errors.h"
#include "transport/lane_endpoint.h"
#include "transport/shm_queue.h"

using namespace crashlink::transport;
using namespace std::chrono_literals;

namespace {

/// A fresh folder for one test's lane files, removed with everything in it at the end.
struct Folder {
  std::filesystem::path dir;
  explicit Folder(const std::string& tag)
      : dir(std::filesystem::temp_directory_path() /
            ("crashlink-shm-test-" + std::to_string(::getpid()) + "-" + tag)) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string prefix() const { return (dir / "lane").string(); }
};

std::string message(int k, std::size_t n) {
  std::string s(n, '\0');
  for (std::size_t i = 0; i < n; ++i)
    s[i] = static_cast<char>((k * 131 + static_cast<int>(i)) & 0xff);
  return s;
}

}  // namespace

TEST(ShmQueue, KeepsWholeMessagesInOrderAcrossTheWrapAround) {
  const Folder folder("wrap");
  const auto path = folder.prefix() + ".q";
  auto in = ShmQueue::create(path, 4096);
  auto out = ShmQueue::open(path);
  ASSERT_TRUE(out.has_value());
  // 1000-byte messages through a 4096-byte ring: the 5th one wraps; 40 of them pass it 10 times.
  int expect = 0;
  for (int k = 0; k < 40; ++k) {
    out->push(message(k, 1000 + static_cast<std::size_t>(k % 7)), 100ms);
    if (k % 3 == 2) continue;  // let two wait now and then
    while (auto m = in.pop()) {
      ASSERT_EQ(*m, message(expect, 1000 + static_cast<std::size_t>(expect % 7))) << expect;
      ++expect;
    }
  }
  while (auto m = in.pop()) ++expect;
  EXPECT_EQ(expect, 40);
  EXPECT_TRUE(in.empty());
}

TEST(ShmQueue, RefusesAMessageLargerThanTheRingAndReportsAReaderThatDoesNotRead) {
  const Folder folder("full");
  const auto path = folder.prefix() + ".q";
  auto in = ShmQueue::create(path, 4096);
  auto out = ShmQueue::open(path);
  ASSERT_TRUE(out.has_value());
  try {
    out->push(std::string(5000, 'x'), 10ms);
    ADD_FAILURE() << "a 5000-byte message went into a 4096-byte ring";
  } catch (const TransportError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("5000 bytes"), std::string::npos) << what;
    EXPECT_NE(what.find("--no-lanes"), std::string::npos) << what;
  }
  out->push(std::string(3000, 'a'), 10ms);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(out->push(std::string(3000, 'b'), 30ms), TransportError);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 30ms);
  EXPECT_EQ(in.pop()->size(), 3000u);       // the first one is intact
  out->push(std::string(3000, 'b'), 10ms);  // and there is room again
  EXPECT_EQ(in.pop(), std::string(3000, 'b'));
}

TEST(ShmQueue, OpensOnlyACompleteFileOfItsKind) {
  const Folder folder("kind");
  const auto prefix = folder.prefix();
  EXPECT_FALSE(ShmQueue::open(prefix + ".none").has_value());
  auto bell = ShmDoorbell::create(prefix + ".bell");
  EXPECT_FALSE(ShmQueue::open(prefix + ".bell").has_value());  // a doorbell is not a queue
  EXPECT_TRUE(ShmDoorbell::open(prefix + ".bell").has_value());
}

TEST(ShmLane, ASleepingReaderIsWokenBySend) {
  const Folder folder("wake");
  const auto prefix = folder.prefix();
  ShmLaneIn in(prefix);
  in.add_partner("fine");
  ShmLaneOut out(in.endpoint(), "fine", 1000ms);
  EXPECT_FALSE(in.receive(5ms).has_value());
  std::thread sender([&] {
    std::this_thread::sleep_for(50ms);
    out.send("hello");
  });
  const auto t0 = std::chrono::steady_clock::now();
  const auto m = in.receive(5000ms);  // sleeps on the doorbell until the send
  const auto waited = std::chrono::steady_clock::now() - t0;
  sender.join();
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->first, "fine");
  EXPECT_EQ(m->second, "hello");
  EXPECT_LT(waited, 4000ms) << "woken by the timeout, not by the doorbell";
}

// A receiver keeps its files until every sender has opened them (daemon_lanes.h
// hold_until_opened): all_opened() says so only once each partner's end has opened, and after
// the receiver has gone, a sender that had opened still sends into its mapping.
TEST(ShmLane, SaysWhenEverySenderHasOpenedItsQueue) {
  const Folder folder("opened");
  const auto prefix = folder.prefix();
  auto in = std::make_unique<ShmLaneIn>(prefix);
  in->add_partner("fine");
  in->add_partner("coarse");
  EXPECT_TRUE(std::filesystem::exists(prefix + ".from.fine"));
  ShmLaneOut fine(in->endpoint(), "fine", 1000ms);
  ShmLaneOut coarse(in->endpoint(), "coarse", 1000ms);
  EXPECT_FALSE(in->all_opened());
  fine.open();
  EXPECT_FALSE(in->all_opened()) << "coarse has not opened its queue";
  coarse.send("first");
  EXPECT_TRUE(in->all_opened());
  in.reset();  // the receiver ends: its files go
  EXPECT_FALSE(std::filesystem::exists(prefix + ".from.fine"));
  EXPECT_NO_THROW(fine.send("nobody reads this")) << "an opened ring outlives its file's name";
  // A sender that had not opened finds nothing, and says which files and how long it waited.
  ShmLaneOut late(ShmLaneIn(folder.prefix() + "2").endpoint(), "fine", 50ms);
  try {
    late.open();
    ADD_FAILURE() << "opened the files of a receiver that has ended";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("did not appear within 50 ms"), std::string::npos)
        << e.what();
  }
}

TEST(ShmLane, CarriesMessagesBetweenTwoProcesses) {
  const Folder folder("fork");
  const auto prefix = folder.prefix();
  ShmLaneIn in(prefix);
  in.add_partner("child");
  const std::string endpoint = in.endpoint();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    int code = 0;
    try {
      ShmLaneOut out(endpoint, "child", 2000ms);
      for (int k = 0; k < 2000; ++k) out.send(message(k, 20000));  // 40 MB through a 4 MiB ring
    } catch (...) {
      code = 1;
    }
    ::_exit(code);
  }
  int received = 0;
  while (received < 2000) {
    auto m = in.receive(5000ms);
    if (!m) break;
    ASSERT_EQ(m->second, message(received, 20000)) << received;
    ++received;
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(received, 2000);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(LaneEndpoint, FollowsTheSession) {
  const CurveOptions plain;
  EXPECT_EQ(lane_endpoint_for("inproc://run", "wiper", plain), "inproc://run.lane.wiper");
  EXPECT_EQ(lane_endpoint_for("tcp://127.0.0.1:5555", "wiper", plain), "tcp://127.0.0.1:*");
  // Beyond loopback: this host's address on the route there (none without a route), never
  // loopback, an ephemeral port.
  const auto far = lane_endpoint_for("tcp://10.1.2.3:5555", "wiper", plain);
  EXPECT_TRUE(far.empty() ||
              (far.rfind("tcp://", 0) == 0 && far.find("127.") == std::string::npos &&
               far.substr(far.size() - 2) == ":*"))
      << far;
  const auto ipc = lane_endpoint_for("ipc:///tmp/run/coordinator.sock", "wiper", plain);
  EXPECT_EQ(ipc.rfind("shm://", 0), 0u) << ipc;
  EXPECT_NE(ipc.find(".wiper"), std::string::npos) << ipc;
  CurveOptions forced;
  forced.force = true;
  EXPECT_EQ(lane_endpoint_for("ipc:///tmp/run/coordinator.sock", "wiper", forced), "");
}

// Issue 20 item 12: a SIGKILLed run leaves its rings behind (nobody is left to remove them); the
// next run's coordinator removes exactly the files whose owner died. A live owner holds a flock
// on its file, so another run's lanes on the same machine are left alone.
TEST(ShmOrphans, OnlyTheFilesOfDeadOwnersAreReclaimed) {
  Folder f("orphans");
  const std::string live = f.prefix() + ".from.live";
  const ShmQueue owned = ShmQueue::create(live, 4096);

  // a ring whose owner process died: created in a child that exits without its destructors
  const std::string dead = f.prefix() + ".from.dead";
  const pid_t child = ::fork();
  if (child == 0) {
    [[maybe_unused]] auto* leaked = new ShmQueue(ShmQueue::create(dead, 4096));
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(std::filesystem::exists(dead));
  // a half-written file of that dead process, and one of this live process
  const std::string dead_tmp = f.prefix() + ".bell.tmp" + std::to_string(child);
  const std::string live_tmp = f.prefix() + ".bell.tmp" + std::to_string(::getpid());
  std::ofstream(dead_tmp) << "x";
  std::ofstream(live_tmp) << "x";

  EXPECT_EQ(reclaim_orphan_shm_files(f.dir.string(), "lane"), 2u);
  EXPECT_FALSE(std::filesystem::exists(dead));
  EXPECT_FALSE(std::filesystem::exists(dead_tmp));
  EXPECT_TRUE(std::filesystem::exists(live)) << "a live owner's ring was removed";
  EXPECT_TRUE(std::filesystem::exists(live_tmp));
  EXPECT_EQ(reclaim_orphan_shm_files(f.dir.string(), "other-prefix"), 0u);
  EXPECT_EQ(owned.path(), live);
}
