// run/checkpoint_store.h: a piece that runs ahead of the others never removes an instant that
// a restart still needs, a checkpoint whose files changed after its commit is found, and the
// pieces that own checkpoints are listed.
#include "solver/run/checkpoint_store.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using crashlink::run::begin_checkpoint;
using crashlink::run::checkpoint_owners;
using crashlink::run::commit_checkpoint;
using crashlink::run::complete_instants;
using crashlink::run::list_checkpoints;
using crashlink::run::list_sound_checkpoints;
namespace fs = std::filesystem;

namespace {

struct Folder {
  fs::path dir;
  explicit Folder(const std::string& name)
      : dir(fs::temp_directory_path() / ("crashlink_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Folder() {
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
  }
  std::string out() const { return dir.string(); }
};

/// One piece's checkpoint at `t`: a state file and a copy of a result file, committed.
void write_piece(const std::string& out, std::int64_t t, const std::string& who,
                 const std::vector<std::string>& pieces) {
  const fs::path tmp = begin_checkpoint(out, t, who);
  std::ofstream(tmp / "state.bin") << "state of " << who << " at " << t;
  std::ofstream(tmp / (who + ".h5")) << std::string(3000, 'r') << t;
  commit_checkpoint(out, t, who, pieces);
}

}  // namespace

// Three pieces commit instants 1..12 in a random interleaving, each at most `lag` instants ahead
// of the slowest (the coordinator writes only once every interface's rows reached an instant, so
// it can trail the daemons by many). After every commit: every instant complete in all pieces
// so far, down to the newest 3, is still there, and no piece lost an instant the slowest has not
// yet passed. The rule before (each piece keeps its own newest 3) removed instants the
// coordinator was about to write and left no common instant.
TEST(CheckpointStore, APieceRunningAheadRemovesNothingARestartNeeds) {
  const std::vector<std::string> pieces = {"fine", "coarse", "coordinator"};
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Folder f("ckstore_ahead");
    std::mt19937 rng(seed);
    std::vector<std::int64_t> next(pieces.size(), 1);
    const std::int64_t last = 12;
    const std::int64_t lag = 1 + static_cast<std::int64_t>(seed % 6);
    while (true) {
      std::vector<std::size_t> can;
      const std::int64_t slowest = *std::min_element(next.begin(), next.end());
      for (std::size_t k = 0; k < pieces.size(); ++k)
        if (next[k] <= last && next[k] < slowest + lag) can.push_back(k);
      if (can.empty()) break;
      const std::size_t k = can[rng() % can.size()];
      write_piece(f.out(), next[k], pieces[k], pieces);
      ++next[k];
      const std::int64_t done_by_all = *std::min_element(next.begin(), next.end()) - 1;
      const auto complete = complete_instants(f.out(), pieces);
      if (done_by_all >= 1) {
        ASSERT_FALSE(complete.empty()) << "seed " << seed << ": no instant that every piece has";
        ASSERT_EQ(complete.back(), done_by_all) << "seed " << seed;
        ASSERT_GE(complete.size(), std::min<std::int64_t>(3, done_by_all)) << "seed " << seed;
      }
      // every piece still has each instant from the slowest piece's newest on
      for (std::size_t j = 0; j < pieces.size(); ++j) {
        const auto mine = list_checkpoints(f.out(), pieces[j]);
        for (std::int64_t t = std::max<std::int64_t>(1, done_by_all); t < next[j]; ++t)
          ASSERT_TRUE(std::binary_search(mine.begin(), mine.end(), t))
              << "seed " << seed << ": " << pieces[j] << " lost instant " << t;
      }
    }
    crashlink::run::prune_checkpoints(f.out(), pieces, pieces);
    for (const auto& who : pieces)
      EXPECT_EQ(list_checkpoints(f.out(), who), (std::vector<std::int64_t>{10, 11, 12}))
          << "seed " << seed << " " << who;
  }
}

TEST(CheckpointStore, AFileChangedAfterTheCommitIsFoundAndNamed) {
  Folder f("ckstore_damage");
  const std::vector<std::string> pieces = {"body"};
  for (std::int64_t t = 1; t <= 3; ++t) write_piece(f.out(), t, "body", pieces);
  EXPECT_EQ(list_sound_checkpoints(f.out(), "body"), (std::vector<std::int64_t>{1, 2, 3}));

  // one flipped byte in the newest checkpoint's copy of the result file
  const fs::path h5 = fs::path(crashlink::run::checkpoint_folder(f.out(), 3, "body")) / "body.h5";
  {
    std::fstream io(h5, std::ios::in | std::ios::out | std::ios::binary);
    io.seekp(1234);
    io.put('X');
  }
  std::vector<std::string> damaged;
  EXPECT_EQ(list_sound_checkpoints(f.out(), "body", &damaged), (std::vector<std::int64_t>{1, 2}));
  ASSERT_EQ(damaged.size(), 1u);
  EXPECT_NE(damaged[0].find("body.h5: FNV-1a"), std::string::npos) << damaged[0];
  EXPECT_NE(damaged[0].find("(the file was changed)"), std::string::npos) << damaged[0];

  // truncated, and removed
  const fs::path state =
      fs::path(crashlink::run::checkpoint_folder(f.out(), 2, "body")) / "state.bin";
  fs::resize_file(state, 4);
  fs::remove(fs::path(crashlink::run::checkpoint_folder(f.out(), 1, "body")) / "body.h5");
  damaged.clear();
  EXPECT_TRUE(list_sound_checkpoints(f.out(), "body", &damaged).empty());
  ASSERT_EQ(damaged.size(), 3u);
  EXPECT_NE(damaged[0].find("body.h5: missing"), std::string::npos) << damaged[0];
  EXPECT_NE(damaged[1].find("state.bin: 4 bytes"), std::string::npos) << damaged[1];

  // a folder without a manifest (written by a version before it) is not offered either
  fs::create_directories(crashlink::run::checkpoint_folder(f.out(), 9, "body"));
  damaged.clear();
  EXPECT_TRUE(list_sound_checkpoints(f.out(), "body", &damaged).empty());
  EXPECT_NE(damaged.back().find("no MANIFEST"), std::string::npos) << damaged.back();
}

// What a restart is offered (a mono run refuses a coupled run's folder and the reverse, by the
// pieces in it): every piece with a committed checkpoint, once each, sorted; a piece still writing
// (its .tmp folder) is not one.
TEST(CheckpointStore, OwnersAreThePiecesWithACommittedCheckpoint) {
  Folder f("ckstore_owners");
  EXPECT_TRUE(checkpoint_owners(f.out()).empty());
  const std::vector<std::string> pieces = {"wiper", "body", "coordinator"};
  for (const std::int64_t t : {10, 20}) write_piece(f.out(), t, "wiper", pieces);
  write_piece(f.out(), 10, "body", pieces);
  (void)begin_checkpoint(f.out(), 20, "coordinator");  // not committed
  EXPECT_EQ(checkpoint_owners(f.out()), (std::vector<std::string>{"body", "wiper"}));
}
