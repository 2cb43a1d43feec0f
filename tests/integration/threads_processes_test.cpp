// Issue 24 item 1 over the programs: `crashlink run --threads N` gives the run of one thread to the
// bit (histories, probes, contacts, field states), in mono and with every daemon of a coupled run
// on N threads (multi over ipc, split), on the CI head-impact scene cut at 4 ms.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "tests/integration/process_test_support.h"
#include "tests/integration/result_compare.h"
#include "tests/integration/shell_command.h"

namespace {

namespace fs = std::filesystem;
using crashlink::proc_test::bin;
using crashlink::proc_test::fresh_dir;

/// The CI scene cut at 4 ms (the headform on the hood from about 2.5 ms: contact, plasticity,
/// the wiper's links): a third of its cycles, so that the runs on more threads than a busy
/// machine's free cores stay short (each cycle waits for every thread of the team).
std::string scenario() {
  static const std::string path = [] {
    std::ifstream in(std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/head_impact_small.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string from = "end_time: 0.012", to = "end_time: 0.004";
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("head_impact_small.yaml: no " + from);
    text.replace(at, from.size(), to);
    return crashlink::proc_test::write_file(fresh_dir("threads_scene") / "head_impact_4ms.yaml",
                                            text);
  }();
  return path;
}

/// Runs the scene with `mode` and `threads` into a fresh folder; returns its result.h5.
std::string run(const std::string& mode, int threads) {
  const fs::path out = fresh_dir("threads_" + mode + "_" + std::to_string(threads));
  int status = -1;
  const std::string log = crashlink::testing::run_command(
      bin("crashlink") + " run " + scenario() + " --mode " + mode + " --quiet --threads " +
          std::to_string(threads) + " --out " + out.string(),
      status);
  EXPECT_EQ(status, 0) << log;
  return (out / "result.h5").string();
}

}  // namespace

TEST(ThreadsOverProcesses, MonoOn3ThreadsIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("mono", 1), run("mono", 3));
}

TEST(ThreadsOverProcesses, MultiWith2ThreadsPerDaemonIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("multi", 1), run("multi", 2));
}

TEST(ThreadsOverProcesses, SplitWith2ThreadsPerDaemonIsTheRunOf1) {
  crashlink::testing::expect_same_results(run("split", 1), run("split", 2));
}

// --domain-threads: the wiper's daemon on 2 threads, the body's on 1 (--threads), the run the
// same to the bit; the summary's threads column says which daemon ran on what. A name that is no
// domain of the run is a usage error naming the domains.
TEST(ThreadsOverProcesses, ThreadsNamedPerDomainReachTheirDaemons) {
  const fs::path out = fresh_dir("threads_named");
  int status = -1;
  const std::string log = crashlink::testing::run_command(
      bin("crashlink") + " run " + scenario() +
          " --mode multi --quiet --threads 1 --domain-threads wiper=2 --out " + out.string(),
      status);
  ASSERT_EQ(status, 0) << log;
  EXPECT_NE(log.find("threads per domain: wiper 2 body 1"), std::string::npos) << log;
  crashlink::testing::expect_same_results(run("multi", 1), (out / "result.h5").string());
  const auto row = [&](const std::string& domain) {
    const auto at = log.find("\n" + domain + " ");
    return at == std::string::npos ? std::string()
                                   : log.substr(at + 1, log.find('\n', at + 1) - at - 1);
  };
  ASSERT_FALSE(row("wiper").empty()) << log;
  ASSERT_FALSE(row("body").empty()) << log;
  EXPECT_EQ(row("wiper").back(), '2') << log;
  EXPECT_EQ(row("body").back(), '1') << log;
  const std::string bad = crashlink::testing::run_command(
      bin("crashlink") + " run " + scenario() + " --mode multi --domain-threads bonnet=2 --out " +
          (out / "bad").string(),
      status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << status << "\n" << bad;
  EXPECT_NE(bad.find("this run has no domain 'bonnet'; its domains: 'wiper', 'body'"),
            std::string::npos)
      << bad;
  // mono has no domains to name; a sign or a blank is not a count
  for (const char* args :
       {" --mode mono --domain-threads wiper=2", " --mode multi --domain-threads wiper=+2",
        " --mode multi --domain-threads wiper=2,wiper=1"}) {
    const std::string refused = crashlink::testing::run_command(
        bin("crashlink") + " run " + scenario() + args + " --out " + (out / "refused").string(),
        status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << args << "\n" << refused;
    EXPECT_NE(refused.find("--domain-threads"), std::string::npos) << refused;
  }
}

TEST(ThreadsOverProcesses, TheFairClockRunsMonoOnTheCoupledRunsCores) {
  // multi, one thread per daemon (two domains), against mono on 2 threads: Table 1 shows the
  // threads and says the wall-clock gain is on equal cores; on 1 thread it names the flag.
  const fs::path out = fresh_dir("threads_fair");
  for (const char* ref_threads : {"2", "1"}) {
    int status = -1;
    const std::string log = crashlink::testing::run_command(
        bin("crashlink") + " run " + scenario() +
            " --mode multi --quiet --reference mono --reference-threads " + ref_threads +
            " --out " + out.string(),
        status);
    ASSERT_EQ(status, 0) << log;
    if (std::string(ref_threads) == "2") {
      EXPECT_NE(log.find("cores: reference 2 threads, run 2 solver threads: the wall-clock gain "
                         "is on equal cores"),
                std::string::npos)
          << log;
      EXPECT_NE(log.find("\nthreads "), std::string::npos) << "no threads row in Table 1\n" << log;
    } else {
      EXPECT_NE(log.find("cores: reference 1 thread, run 2 solver threads (for the gain on equal "
                         "cores: --reference-threads 2)"),
                std::string::npos)
          << log;
    }
  }
}
