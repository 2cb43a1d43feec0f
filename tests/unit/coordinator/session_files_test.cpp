// The coordinator's clean-up of lane files that killed runs left (coordinator/session_files.h):
// beside the socket, where the rings go without /dev/shm, as in /dev/shm. A live ring stays.
#include "coordinator/session_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "transport/shm_queue.h"

namespace fs = std::filesystem;

TEST(SessionFiles, LaneFilesOfKilledRunsBesideTheSocketAreReclaimed) {
  const fs::path dir =
      fs::temp_directory_path() / ("crashlink-session-files-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string socket = (dir / "coordinator.sock").string();
  std::ofstream(socket + ".fine.from.coarse") << "a ring whose owner was killed";
  std::ofstream(socket + ".fine.bell") << "its bell";
  std::ofstream(dir / "notes.txt") << "not a lane";
  {
    // a live run's ring, its creator holding its lock
    auto live = crashlink::transport::ShmQueue::create(socket + ".mid.from.fine", 4096);
    crashlink::coordinator::reclaim_orphan_lanes("ipc://" + socket, nullptr);
    EXPECT_FALSE(fs::exists(socket + ".fine.from.coarse"));
    EXPECT_FALSE(fs::exists(socket + ".fine.bell"));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_TRUE(fs::exists(socket + ".mid.from.fine")) << "a live ring was removed";
  }
  // tcp and inproc sessions have no rings: nothing is touched
  std::ofstream(socket + ".fine.bell") << "again";
  crashlink::coordinator::reclaim_orphan_lanes("tcp://127.0.0.1:5555", nullptr);
  EXPECT_TRUE(fs::exists(socket + ".fine.bell"));
  fs::remove_all(dir);
}
