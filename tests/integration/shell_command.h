#pragma once
// Runs a shell command for the end-to-end tests of the `crashlink` executable: its stdout and
// stderr together, and its wait status (pclose's).
#include <array>
#include <cstdio>
#include <string>

namespace crashlink::testing {

inline std::string run_command(const std::string& cmd, int& status) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) {
    status = -1;
    return out;
  }
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  status = pclose(p);
  return out;
}

}  // namespace crashlink::testing
