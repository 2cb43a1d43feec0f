// The command lines of the three programs (docs/processes.md, "Exit codes"): every usage error of
// `crashlink` (with each subcommand, and without one), crashlink-solver and crashlink-coordinator
// exits 2 (kExitInput) with CLI11's message and the --help to run, on stderr; `crashlink`
// alone prints the usage and exits 2; --help and --version exit 0, --version printing the
// program, crashlink's version and the wire protocol version. Before, CLI11's own codes came out
// (105 a value out of range, 106 a missing option or subcommand, 109 an unknown argument).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/exit_codes.h"
#include "proto/protocol_version.h"
#include "tests/integration/shell_command.h"

using crashlink::testing::run_command;

namespace {

std::string bin(const std::string& program) {
  return std::string(CRASHLINK_BINARY_DIR) + "/apps/" + program;
}

std::string scenario() {
  return std::string(CRASHLINK_SOURCE_DIR) + "/scenarios/plate_impact_small.yaml";
}

struct Outcome {
  int code = -1;
  std::string out;  ///< stdout and stderr
};

Outcome run(const std::string& program, const std::string& args) {
  Outcome o;
  int status = -1;
  o.out = run_command(bin(program) + " " + args + " </dev/null", status);
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

/// A usage error: exit 2, "COMMAND: usage error: <CLI11's message>", and the --help to run.
void expect_usage_error(const std::string& program, const std::string& args,
                        const std::string& command, const std::string& cli11_says) {
  const auto o = run(program, args);
  SCOPED_TRACE(program + " " + args);
  EXPECT_EQ(o.code, crashlink::kExitInput) << o.out;
  EXPECT_NE(o.out.find(command + ": usage error: "), std::string::npos) << o.out;
  EXPECT_NE(o.out.find(cli11_says), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("Run `" + command + " --help`"), std::string::npos) << o.out;
}

/// The subcommands `crashlink --help` lists.
std::vector<std::string> subcommands() {
  const auto o = run("crashlink", "--help");
  std::vector<std::string> names;
  const auto at = o.out.find("Subcommands:\n");
  if (at == std::string::npos) return names;
  std::istringstream lines(o.out.substr(at + 13));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string name;
    if (line.rfind("  ", 0) == 0 && words >> name) names.push_back(name);
  }
  return names;
}

}  // namespace

TEST(CliUsage, CrashlinkWithoutSubcommandPrintsUsageAndExits2) {
  const auto o = run("crashlink", "");
  EXPECT_EQ(o.code, crashlink::kExitInput) << o.out;
  EXPECT_NE(o.out.find("Usage:"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("Subcommands:"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("A subcommand is required"), std::string::npos) << o.out;
  expect_usage_error("crashlink", "frob", "crashlink", "'frob' is not a subcommand");
  expect_usage_error("crashlink", "--frob", "crashlink", "'--frob' is not an option");
}

TEST(CliUsage, EverySubcommandsUsageErrorExits2) {
  const auto names = subcommands();
  for (const char* known :
       {"run", "hic", "gather", "compare", "report", "advise", "stability-map", "sweep", "keygen"})
    EXPECT_NE(std::find(names.begin(), names.end(), known), names.end()) << known;
  for (const auto& sub : names) {
    // CLI11 reports the first problem it finds: a missing positional or option, if any
    expect_usage_error("crashlink", sub + " --no-such-flag", "crashlink " + sub, "");
    const auto help = run("crashlink", sub + " --help");
    EXPECT_EQ(help.code, 0) << sub << "\n" << help.out;
    EXPECT_NE(help.out.find("Usage:"), std::string::npos) << help.out;
  }
  // a missing positional (106 before), a value out of a set (105), one too many (109)
  expect_usage_error("crashlink", "run", "crashlink run", "scenario is required");
  expect_usage_error("crashlink", "run " + scenario() + " --mode fast", "crashlink run",
                     "--mode: fast not in {mono,split,multi}");
  expect_usage_error("crashlink", "run " + scenario() + " " + scenario(), "crashlink run",
                     "not expected");
  expect_usage_error("crashlink", "run " + scenario() + " --step-safety 2", "crashlink run",
                     "--step-safety: Value 2 not in range");
  expect_usage_error("crashlink", "hic", "crashlink hic", "is required");
}

TEST(CliUsage, SolverUsageErrorsExit2) {
  const std::string needed = "--connect tcp://127.0.0.1:1 --domain d --scenario " + scenario();
  expect_usage_error("crashlink-solver", "", "crashlink-solver", "--connect is required");
  expect_usage_error("crashlink-solver", needed + " --no-such-flag", "crashlink-solver",
                     "--no-such-flag");
  expect_usage_error("crashlink-solver", needed + " --step-safety 2", "crashlink-solver",
                     "--step-safety: Value 2 not in range");
  expect_usage_error("crashlink-solver", needed + " --heartbeat-ms soon", "crashlink-solver",
                     "--heartbeat-ms");
  expect_usage_error("crashlink-solver", needed + " --coupling glue", "crashlink-solver",
                     "--coupling: glue not in {layer,paper,lts}");
}

TEST(CliUsage, CoordinatorUsageErrorsExit2) {
  const std::string needed = "--bind tcp://127.0.0.1:* --scenario " + scenario();
  expect_usage_error("crashlink-coordinator", "", "crashlink-coordinator", "--bind is required");
  expect_usage_error("crashlink-coordinator", needed + " --no-such-flag", "crashlink-coordinator",
                     "--no-such-flag");
  expect_usage_error("crashlink-coordinator", needed + " --mode mono", "crashlink-coordinator",
                     "--mode: mono not in {split,multi}");
  expect_usage_error("crashlink-coordinator", needed + " --join-timeout-ms 0",
                     "crashlink-coordinator", "--join-timeout-ms: Value 0 not in range");
  expect_usage_error("crashlink-coordinator", "--bind", "crashlink-coordinator", "--bind");
}

TEST(CliUsage, HelpAndVersionExit0) {
  std::string crashlink_version;
  for (const std::string program : {"crashlink", "crashlink-solver", "crashlink-coordinator"}) {
    const auto help = run(program, "--help");
    EXPECT_EQ(help.code, 0) << program << "\n" << help.out;
    EXPECT_NE(help.out.find("--version"), std::string::npos) << help.out;
    const auto v = run(program, "--version");
    EXPECT_EQ(v.code, 0) << program << "\n" << v.out;
    // "PROGRAM X.Y.Z (wire protocol N)", one version for the three
    std::smatch m;
    ASSERT_TRUE(std::regex_match(v.out, m,
                                 std::regex(program + " ([0-9]+\\.[0-9]+\\.[0-9]+[^ ]*) \\(wire "
                                                      "protocol ([0-9]+)\\)\n")))
        << v.out;
    EXPECT_EQ(m[2].str(), std::to_string(crashlink::wire::kProtocolVersion)) << v.out;
    if (crashlink_version.empty()) crashlink_version = m[1].str();
    EXPECT_EQ(m[1].str(), crashlink_version) << program;
  }
}
