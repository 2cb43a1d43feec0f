#pragma once
// Exit codes of `crashlink`, `crashlink-solver` and `crashlink-coordinator` (docs/processes.md).
// One table for the three, so that a launcher can tell from a child's code what happened.
namespace crashlink {

inline constexpr int kExitOk = 0;
/// Bad input: command line, scenario file, unknown domain; also a daemon refused by the
/// coordinator for another protocol version or another scenario (the fix is in the invocation).
inline constexpr int kExitInput = 2;
/// The guard stopped the run (a blow-up in a domain); the output up to then is kept and finite.
inline constexpr int kExitNumerical = 3;
/// A bug: an unexpected exception.
inline constexpr int kExitInternal = 4;
/// The run was stopped by another process: a daemon or the coordinator died, went silent,
/// reported an error or broke the protocol; or a socket failed. The message names the culprit.
inline constexpr int kExitPeer = 5;
/// A file could not be written or read back: disk full, read-only file system, no permission,
/// `--out` names a file. The message names the file and the system's reason; what was written
/// before stays readable.
inline constexpr int kExitIo = 6;
/// Stopped on request: SIGINT or SIGTERM (Ctrl-C, `kill PID`, a batch scheduler's cancel) to the
/// launcher or to any process of the run; every process stops within 1 s, files flushed.
inline constexpr int kExitStopped = 7;

}  // namespace crashlink
