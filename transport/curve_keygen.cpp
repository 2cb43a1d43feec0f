#include "transport/curve_keygen.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/errors.h"
#include "transport/curve_errors.h"
#include "transport/curve_key.h"
#include "transport/curve_support.h"
#include "transport/detail/zmq.h"

namespace crashlink::transport {

namespace {

/// Creates `path` with `mode` (the mode is set at creation: never readable by others, not even
/// for a moment) and writes `text`.
void write_new(const std::string& path, const std::string& text, mode_t mode, bool overwrite) {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (overwrite ? O_TRUNC : O_EXCL);
  const int fd = ::open(path.c_str(), flags, mode);
  if (fd < 0) {
    const int err = errno;
    if (err == EEXIST) {
      throw InputError(
          fmt::format("{} exists already; fix: choose another --out PREFIX, or pass "
                      "--force to replace the key pair (daemons and coordinators "
                      "using the old keys will be refused)",
                      path));
    }
    throw InputError(fmt::format("cannot create {}: {}; fix: choose a writable --out PREFIX", path,
                                 std::strerror(err)));
  }
  // An existing file keeps its mode on O_TRUNC: set it.
  bool ok = ::fchmod(fd, mode) == 0;
  std::size_t done = 0;
  while (ok && done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += static_cast<std::size_t>(n);
  }
  const int err = errno;
  ok = ::close(fd) == 0 && ok;
  if (!ok) {
    throw InputError(fmt::format("cannot write {}: {}", path, std::strerror(err)));
  }
}

}  // namespace

CurveKeyPair make_curve_keypair() {
  require_curve("crashlink keygen");
  std::array<char, kCurveKeyChars + 1> pub{};
  std::array<char, kCurveKeyChars + 1> sec{};
  if (zmq_curve_keypair(pub.data(), sec.data()) != 0) {
    throw CurveUnavailableError(
        fmt::format("zmq_curve_keypair failed: {}", zmq_strerror(zmq_errno())));
  }
  return {std::string(pub.data(), kCurveKeyChars), std::string(sec.data(), kCurveKeyChars)};
}

CurveKeyFiles write_curve_keypair(const std::string& prefix, bool overwrite) {
  if (prefix.empty() || prefix.back() == '/') {
    throw InputError(
        fmt::format("--out '{}' is not a file prefix; fix: e.g. --out keys/wiper "
                    "(writes keys/wiper.key and keys/wiper.pub)",
                    prefix));
  }
  const CurveKeyPair pair = make_curve_keypair();
  CurveKeyFiles files{prefix + ".key", prefix + ".pub", pair.public_key};
  if (!overwrite) {
    // Both checked before either is written: never half a pair.
    for (const auto& f : {files.secret_file, files.public_file}) {
      std::error_code ec;
      if (std::filesystem::exists(f, ec)) write_new(f, {}, 0, false);  // throws "exists already"
    }
  }
  const std::string name = std::filesystem::path(prefix).filename().string();
  write_new(files.secret_file,
            fmt::format("# crashlink CURVE secret key '{}' (Z85). Keep it private: mode 0600, "
                        "never copied off this host.\n# Its public key is in {}.pub.\n{}\n",
                        name, name, pair.secret_key),
            S_IRUSR | S_IWUSR, overwrite);
  write_new(files.public_file,
            fmt::format("# crashlink CURVE public key '{}' (Z85) of {}.key. A daemon's goes into "
                        "the coordinator's --curve-authorized-keys file;\n# the coordinator's "
                        "is every daemon's --curve-server-key.\n{}\n",
                        name, name, pair.public_key),
            S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH, overwrite);
  return files;
}

}  // namespace crashlink::transport
