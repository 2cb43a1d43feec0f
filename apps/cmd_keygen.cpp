#include "apps/cmd_keygen.h"

#include <cstdio>

#include "transport/curve_keygen.h"

namespace crashlink::apps {

CLI::App* add_keygen_command(CLI::App& app, KeygenOptions& o) {
  auto* cmd = app.add_subcommand(
      "keygen",
      "write a CURVE key pair: PREFIX.key (secret, mode 0600) and PREFIX.pub (public), for "
      "crashlink-coordinator and crashlink-solver over a network (docs/processes.md)");
  cmd->add_option("--out", o.out, "file prefix, e.g. keys/wiper (writes keys/wiper.key, .pub)")
      ->required();
  cmd->add_flag("--force", o.force, "replace existing PREFIX.key and PREFIX.pub");
  return cmd;
}

int run_keygen(const KeygenOptions& o) {
  const auto files = transport::write_curve_keypair(o.out, o.force);
  std::printf(
      "crashlink keygen: wrote %s (secret key, mode 0600) and %s (public key %s)\n"
      "  coordinator: --curve-secret-key %s; give %s to every daemon as --curve-server-key\n"
      "  daemon: --curve-secret-key %s; append %s to the coordinator's --curve-authorized-keys "
      "file\n",
      files.secret_file.c_str(), files.public_file.c_str(), files.public_key.c_str(),
      files.secret_file.c_str(), files.public_file.c_str(), files.secret_file.c_str(),
      files.public_file.c_str());
  return 0;
}

}  // namespace crashlink::apps
