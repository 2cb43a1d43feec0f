#pragma once
// SIGTERM / SIGINT -> a flag the long loops poll (coordinator: every poll; daemon: every cycle),
// so that a stopped process still tells its peers, writes its file and exits with a message.
#include <atomic>
#include <csignal>

namespace crashlink::apps {

inline std::atomic<bool>& stop_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

inline void install_stop_handlers() {
  auto handler = [](int) { stop_flag().store(true); };
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

}  // namespace crashlink::apps
