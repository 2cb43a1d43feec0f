#include "apps/python_script.h"

#include <cstdio>
#include <cstdlib>

namespace crashlink::apps {

namespace {

/// A shell word: 'text' with every ' written '\''.
std::string shell_word(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

}  // namespace

int run_python_script(const std::string& script, const char* env_override,
                      const std::vector<std::string>& args, const char* who) {
  const char* env = env_override ? std::getenv(env_override) : nullptr;
  const std::string path =
      env ? std::string(env) : std::string(CRASHLINK_SOURCE_DIR) + "/tools/" + script;
  std::string cmd = "/usr/bin/python3 " + shell_word(path);
  for (const auto& a : args) cmd.append(" ").append(shell_word(a));
  std::fflush(stdout);
  const int status = std::system(cmd.c_str());
  if (status != 0) {
    std::fprintf(stderr,
                 "crashlink %s: the plotting script failed (%s, status %d); it needs "
                 "/usr/bin/python3 with python3-matplotlib and python3-h5py "
                 "(tools/install-deps.sh installs them)\n",
                 who, path.c_str(), status);
    return 4;
  }
  return 0;
}

}  // namespace crashlink::apps
