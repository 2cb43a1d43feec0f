// Exit code 4 end to end (docs/processes.md "Exit codes"): an unexpected exception in a daemon,
// injected at a cycle by CRASHLINK_INJECT_INTERNAL_ERROR, ends that daemon with 4 and "internal
// error", the others with 5 naming it, and the launcher with 4; the files written up to then stay
// readable.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
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

TEST(InternalError, AnUnexpectedExceptionInADaemonEndsTheRunWithExit4) {
  const fs::path dir = fresh_dir("internal_error");
  const std::string scenario = crashlink::proc_test::write_file(
      dir / "bar.yaml", crashlink::proc_test::bar_parts_yaml(
                            "bugbar", 2e-3, {{"left", 0.0, 0.2, 20}, {"right", 0.2, 0.4, 10}}));
  int status = -1;
  const std::string out =
      run_command("CRASHLINK_INJECT_INTERNAL_ERROR=right:200 " + bin("crashlink") + " run " +
                      scenario + " --mode multi --quiet --out " + (dir / "out").string(),
                  status);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), crashlink::kExitInternal) << out;
  EXPECT_NE(out.find("domain 'right' exited with code 4"), std::string::npos) << out;
  EXPECT_NE(out.find("internal error: injected at cycle 200"), std::string::npos) << out;
  EXPECT_NE(out.find("domain 'left' exited with code 5"), std::string::npos) << out;
  const crashlink::io::ResultReader r((dir / "out" / "domains" / "right.h5").string());
  EXPECT_FALSE(r.glstat().empty());
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
