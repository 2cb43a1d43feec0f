#pragma once
// What the command lines of `crashlink`, crashlink-solver and crashlink-coordinator share
// (docs/processes.md, "Exit codes"): `--version`, and a usage error as exit 2 (kExitInput)
// with CLI11's message and where to find the options, instead of CLI11's own codes (105, 106,
// 109, ...). `--help` and `--version` print on stdout and exit 0.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "core/exit_codes.h"
#include "crashlink_version.h"
#include "proto/protocol_version.h"

namespace crashlink::apps {

/// `PROGRAM VERSION (wire protocol N)`: what --version prints. Daemons and the coordinator of one
/// run must speak the same wire protocol (the handshake refuses another one).
inline std::string version_text(const std::string& program) {
  return program + " " + CRASHLINK_VERSION + " (wire protocol " +
         std::to_string(wire::kProtocolVersion) + ")";
}

inline void add_version_flag(CLI::App& app, const std::string& program) {
  app.set_version_flag("--version", version_text(program),
                       "print the program, crashlink's version and the wire protocol version");
}

/// The exit code after `app.parse` threw `e`: 0 after --help or --version (printed on stdout by
/// CLI11); otherwise 2 after "PROGRAM [SUBCOMMAND]: usage error: <CLI11's message>" and the
/// --help to run, on stderr. `program` is the executable's name; `what` replaces CLI11's message.
inline int parse_error_exit(CLI::App& app, const CLI::ParseError& e, const std::string& program,
                            const std::string& what = {}) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
  std::string command = program;
  for (const CLI::App* sub = &app;;) {
    const auto chosen = sub->get_subcommands();
    if (chosen.empty()) break;
    sub = chosen.front();
    command += " " + sub->get_name();
  }
  std::fprintf(stderr, "%s: usage error: %s\nRun `%s --help` for the options.\n", command.c_str(),
               what.empty() ? e.what() : what.c_str(), command.c_str());
  return kExitInput;
}

/// "--coupling NAME": one of the registered schemes' names (the tables of
/// solver/daemon/domain_schemes.h and coordinator/coordinator_schemes.h), which CLI11 lists in the
/// option's help with the default.
inline CLI::Option* add_coupling_option(CLI::App& app, std::string& coupling,
                                        const std::vector<std::string>& names,
                                        const std::string& what) {
  return app.add_option("--coupling", coupling, what)
      ->check(CLI::IsMember(names))
      ->capture_default_str();
}

}  // namespace crashlink::apps
