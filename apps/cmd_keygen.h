#pragma once
// `crashlink keygen --out PREFIX` (docs/processes.md, "Security (CURVE)"): a CURVE key pair,
// PREFIX.key (secret, mode 0600) and PREFIX.pub (public), for a coordinator or a daemon that
// talks over a non-loopback network (transport/curve_keygen.h).
#include <CLI/CLI.hpp>
#include <string>

namespace crashlink::apps {

struct KeygenOptions {
  std::string out;
  bool force = false;
};

CLI::App* add_keygen_command(CLI::App& app, KeygenOptions& options);

/// Writes the pair and prints where and the public key; 0. Errors throw (InputError: files
/// exist or cannot be written; CurveUnavailableError: libzmq without CURVE).
int run_keygen(const KeygenOptions& options);

}  // namespace crashlink::apps
