// The coordinator's clean-up of lane files that killed runs left beside its socket, where the
// rings go on a machine without /dev/shm (coordinator/session_files.h): the dead ones go, a live
// ring and the user's files named like the socket stay.
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
  const std::string socket = (dir / "scene").string();  // --bind ipc://DIR/scene
  std::ofstream(socket + ".fine.from.coarse") << "a ring whose owner was killed";
  std::ofstream(socket + ".fine.bell") << "its bell";
  std::ofstream(socket + ".yaml") << "the user's scenario, named like the socket";
  std::ofstream(socket + ".log") << "and a log";
  std::ofstream(socket + ".bellows.csv") << "and names that only look like a ring's";
  std::ofstream(socket + ".x.from.y.txt") << "too";
  {
    // a live run's ring, its creator holding its lock
    auto live = crashlink::transport::ShmQueue::create(socket + ".mid.from.fine", 4096);
    EXPECT_EQ(crashlink::coordinator::reclaim_lanes_beside_socket(socket), 2u);
    EXPECT_FALSE(fs::exists(socket + ".fine.from.coarse"));
    EXPECT_FALSE(fs::exists(socket + ".fine.bell"));
    EXPECT_TRUE(fs::exists(socket + ".yaml")) << "a user's file was removed";
    EXPECT_TRUE(fs::exists(socket + ".log")) << "a user's file was removed";
    EXPECT_TRUE(fs::exists(socket + ".bellows.csv")) << "a user's file was removed";
    EXPECT_TRUE(fs::exists(socket + ".x.from.y.txt")) << "a user's file was removed";
    EXPECT_TRUE(fs::exists(socket + ".mid.from.fine")) << "a live ring was removed";
  }
  fs::remove_all(dir);
}
