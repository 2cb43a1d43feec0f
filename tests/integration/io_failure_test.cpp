// I/O failures (issue 20 item 3): a file that cannot be written ends every process with exit 6
// (kExitIo) and a message naming the file and the system's reason, never a crash, and what
// was written before stays readable. Before: mono on a 2 MB file system died of SIGSEGV (exit 139,
// HDF5's clean-up at exit after a failed close), multi's three processes too, other failures came
// back as 3, 4 or 5, and a multi run left a 0-byte result.h5.
//
// A full disk is made with a file-size limit (`ulimit -f`, SIGXFSZ ignored: every write past it
// fails with EFBIG, the same path as ENOSPC) so the test needs no privileges; where the test may
// mount (root), a 2 MB tmpfs gives the real ENOSPC too.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/exit_codes.h"
#include "solver/io/result_reader.h"
#include "tests/integration/process_test_support.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using crashlink::proc_test::bin;
using crashlink::proc_test::fresh_dir;
using crashlink::testing::run_command;

const std::string kScenario =
    std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml";

int code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

/// `crashlink run` with every file limited to `limit_kb` KiB (0: no limit).
std::string run_limited(const std::string& mode, const fs::path& out, int limit_kb, int& code,
                        const std::string& extra = {}) {
  std::string cmd = "sh -c 'trap \"\" XFSZ; ";
  if (limit_kb > 0) cmd += "ulimit -f " + std::to_string(limit_kb) + "; ";
  cmd += "exec " + bin("crashlink") + " run " + kScenario + " --mode " + mode + " --quiet " +
         extra + " --out " + out.string() + "'";
  int status = -1;
  const std::string text = run_command(cmd, status);
  code = code_of(status);
  return text;
}

/// The file opens and holds history rows (the rows flushed before the failure).
void expect_readable(const fs::path& h5, const std::string& log) {
  ASSERT_TRUE(fs::exists(h5)) << log;
  EXPECT_GT(fs::file_size(h5), 0u) << h5;
  try {
    const crashlink::io::ResultReader r(h5.string());
    EXPECT_FALSE(r.glstat().empty()) << h5;
  } catch (const std::exception& e) {
    ADD_FAILURE() << h5 << " unreadable after the failure: " << e.what() << "\n" << log;
  }
}

class IoFailure : public ::testing::TestWithParam<std::string> {};

TEST_P(IoFailure, AFullDiskEndsTheRunWithExit6NamingTheFile) {
  const std::string mode = GetParam();
  const fs::path dir = fresh_dir("io_full_" + mode);
  int code = -1;
  // 3 MB per file: the CI scene's result files grow to 3-8 MB
  const std::string log =
      run_limited(mode, dir / "out", 3072, code, mode == "multi" ? "--no-lanes" : "");
  EXPECT_EQ(code, crashlink::kExitIo) << log;
  EXPECT_NE(log.find("I/O error"), std::string::npos) << log;
  EXPECT_NE(log.find("the disk is full"), std::string::npos) << log;
  EXPECT_EQ(log.find("Segmentation"), std::string::npos) << log;
  if (mode == "mono") {
    EXPECT_NE(log.find((dir / "out" / "result.h5").string()), std::string::npos) << log;
    expect_readable(dir / "out" / "result.h5", log);
  } else {
    EXPECT_NE(log.find("ERROR_CODE_IO"), std::string::npos) << log;
    for (const char* d : {"wiper", "body"})
      expect_readable(dir / "out" / "domains" / (std::string(d) + ".h5"), log);
    // a gathered file is there whole or not at all
    const fs::path result = dir / "out" / "result.h5";
    if (fs::exists(result)) expect_readable(result, log);
  }
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Modes, IoFailure, ::testing::Values("mono", "multi"));

TEST(IoFailure, OutNamingAFileIsRefusedWithExit6) {
  const fs::path dir = fresh_dir("io_out_file");
  std::ofstream(dir / "taken") << "not a folder";
  for (const std::string mode : {"mono", "multi"}) {
    int code = -1;
    const std::string log = run_limited(mode, dir / "taken", 0, code);
    EXPECT_EQ(code, crashlink::kExitIo) << mode << "\n" << log;
    EXPECT_NE(log.find((dir / "taken").string()), std::string::npos) << log;
  }
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

// The real ENOSPC where this process may mount a tmpfs (root; CI runs as root), skipped elsewhere.
TEST(IoFailure, ANoSpaceLeftFileSystemEndsMonoWithExit6) {
  const fs::path dir = fresh_dir("io_enospc");
  const fs::path mnt = dir / "small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=2m") != 0)
    GTEST_SKIP() << "cannot mount a 2 MB tmpfs here (not root?): the ulimit tests cover the path";
  int code = -1;
  const std::string log = run_limited("mono", mnt / "out", 0, code);
  EXPECT_EQ(code, crashlink::kExitIo) << log;
  EXPECT_NE(log.find("the disk is full"), std::string::npos) << log;
  expect_readable(mnt / "out" / "result.h5", log);
  ::umount2(mnt.c_str(), MNT_DETACH);
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
