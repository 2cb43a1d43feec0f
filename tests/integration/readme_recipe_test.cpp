// The README's by-hand recipe ("Running on several hosts"), run as the README writes it: the
// commands of the block between `<!-- by-hand recipe: begin` and `<!-- by-hand recipe: end -->`
// are read from README.md and started as separate processes from the source folder, with only
// the build folder (`build/`), the output folder (the word after `--out`) and the loopback port
// (the coordinator binds port `*`, the daemons get the port it prints) substituted. Every
// endpoint must be tcp on 127.0.0.1: nothing leaves the machine. Each process must exit 0 and
// the gathered result must reach the scenario's end time.
//
// Before the programs shared their defaults (apps/shared_defaults.h), crashlink-solver's
// --step-safety defaulted to 1 where `crashlink run`'s is 0.9, and this recipe stopped at
// t = 3.56 ms with exit 3 (body: the fixed step above the shrinking stable step).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "solver/io/result_reader.h"
#include "solver/io/scenario_reader.h"
#include "tests/integration/process_test_support.h"

using namespace crashlink;
using namespace crashlink::proc_test;

namespace {

constexpr const char* kBegin = "<!-- by-hand recipe: begin";
constexpr const char* kEnd = "<!-- by-hand recipe: end -->";

/// One command of the block: its words and whether it ends with `&` (runs in the background).
struct Command {
  std::vector<std::string> words;
  bool background = false;
  std::string text;  ///< as written (for messages)
};

/// The commands of the README's by-hand block: the lines of its ```sh fence, `\` continuations
/// joined, comments dropped. Plain commands only: a quote, `$`, a pipe, a redirection or `;`
/// fails the test (this runner is not a shell).
std::vector<Command> recipe_commands(const std::string& readme) {
  std::vector<Command> out;
  const auto b = readme.find(kBegin);
  const auto e = readme.find(kEnd);
  if (b == std::string::npos || e == std::string::npos || e < b) {
    ADD_FAILURE() << "README.md has no block between '" << kBegin << "' and '" << kEnd << "'";
    return out;
  }
  const std::string block = readme.substr(b, e - b);
  const auto fence = block.find("```sh\n");
  const auto close = block.find("\n```", fence + 1);
  if (fence == std::string::npos || close == std::string::npos) {
    ADD_FAILURE() << "the by-hand recipe block has no ```sh fence:\n" << block;
    return out;
  }
  std::istringstream lines(block.substr(fence + 6, close - fence - 6));
  std::string line, joined;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\\') {
      joined += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    joined += line;
    const auto hash = joined.find('#');
    if (hash != std::string::npos) joined.erase(hash);
    Command c;
    c.text = joined;
    for (const char bad : {'"', '\'', '$', '|', ';', '>', '<', '`'})
      if (joined.find(bad) != std::string::npos)
        ADD_FAILURE() << "the by-hand recipe uses '" << bad
                      << "', which this test does not run: " << joined;
    std::istringstream words(joined);
    for (std::string w; words >> w;) c.words.push_back(w);
    joined.clear();
    if (c.words.empty()) continue;
    if (c.words.back() == "&") {
      c.background = true;
      c.words.pop_back();
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// A process of the recipe and the command it came from.
struct Started {
  std::unique_ptr<Child> child;
  std::string text;
};

void expect_exit_0(Started& s, std::chrono::seconds timeout) {
  const auto st = s.child->wait(timeout);
  ASSERT_TRUE(st.has_value()) << "still running after " << timeout.count() << " s: " << s.text
                              << "\n"
                              << s.child->output();
  EXPECT_EQ(exit_code(*st), 0) << s.text << "\n" << s.child->output();
}

}  // namespace

TEST(ReadmeRecipe, ByHandMultiHostRecipeRunsOnLoopback) {
  const std::string source = CRASHLINK_SOURCE_DIR;
  const auto commands = recipe_commands(read_text(source + "/README.md"));
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto dir = fresh_dir("readme-recipe");
  const RemoveIfPassed cleanup{dir};
  const auto out = dir / "run1";

  int coordinators = 0, solvers = 0, gathers = 0;
  std::string port;      // the coordinator's real port, read back
  std::string scenario;  // as the recipe names it (relative to the source folder)
  std::vector<Started> background;
  for (const auto& c : commands) {
    if (c.words == std::vector<std::string>{"wait"}) {
      for (auto& s : background) expect_exit_0(s, std::chrono::seconds{300});
      background.clear();
      continue;
    }
    std::vector<std::string> argv = c.words;
    // the build folder
    ASSERT_EQ(argv[0].rfind("build/", 0), 0u) << "not a built program: " << c.text;
    argv[0] = std::string(CRASHLINK_BINARY_DIR) + "/" + argv[0].substr(6);
    const std::string program = std::filesystem::path(argv[0]).filename().string();
    coordinators += program == "crashlink-coordinator";
    solvers += program == "crashlink-solver";
    gathers += program == "crashlink" && argv.size() > 1 && argv[1] == "gather";
    for (std::size_t i = 1; i < argv.size(); ++i) {
      std::string& a = argv[i];
      if (argv[i - 1] == "--out") a = out.string();  // the output folder
      if (argv[i - 1] == "--scenario" || (argv[i - 1] == "gather" && i == 2)) scenario = a;
      if (a.find("://") != std::string::npos) {
        // loopback only; the port: any free one for the coordinator, then the one it printed
        const std::string host = "tcp://127.0.0.1:";
        ASSERT_EQ(a.rfind(host, 0), 0u) << "the recipe's endpoints must be on 127.0.0.1: " << a;
        if (argv[i - 1] == "--bind") {
          a = host + "*";
        } else {
          ASSERT_FALSE(port.empty()) << "a daemon before the coordinator: " << c.text;
          a = host + port;
        }
      }
    }
    Started s{std::make_unique<Child>(argv, source), c.text};
    if (program == "crashlink-coordinator") {
      ASSERT_TRUE(s.child->wait_for_output(" for ", std::chrono::seconds{30})) << s.child->output();
      const std::string endpoint = s.child->between("listening on ", " for ");
      port = endpoint.substr(endpoint.rfind(':') + 1);
      ASSERT_FALSE(port.empty()) << s.child->output();
    }
    if (c.background) {
      background.push_back(std::move(s));
    } else {
      expect_exit_0(s, std::chrono::seconds{300});
    }
  }
  for (auto& s : background) expect_exit_0(s, std::chrono::seconds{300});
  EXPECT_EQ(coordinators, 1);
  EXPECT_GE(solvers, 2);
  EXPECT_EQ(gathers, 1);
  ASSERT_FALSE(::testing::Test::HasFailure());

  // The result is complete: every history row and field state up to the end time.
  const auto model = io::read_scenario(source + "/" + scenario);
  const double end = model.controls.end_time_s;
  io::ResultReader r((out / "result.h5").string());
  const auto g = r.glstat();
  ASSERT_FALSE(g.empty());
  EXPECT_NEAR(g.back().time_s, end, 0.5 * model.controls.history_interval_s)
      << "history rows stop early";
  ASSERT_GT(r.state_count(), 0u);
  const double field = model.controls.field_interval_s;
  EXPECT_NEAR(r.state_time(r.state_count() - 1), end, 0.01 * field) << "field states stop early";
  EXPECT_EQ(r.state_count(), static_cast<std::size_t>(std::llround(end / field)) + 1);
  for (const auto& d : model.domains)
    EXPECT_TRUE(std::filesystem::exists(out / "domains" / (d.name + ".h5"))) << d.name;
}
