#pragma once
// CURVE key pairs for `crashlink keygen --out PREFIX` (docs/processes.md, "Security (CURVE)"):
// PREFIX.key holds the secret key (mode 0600, created so that no other user can ever read it)
// and PREFIX.pub the public key, each one Z85 line under a '#' comment saying what it is
// (curve_key.h reads them back).
#include <string>

namespace crashlink::transport {

struct CurveKeyPair {
  std::string public_key;  ///< Z85, 40 characters
  std::string secret_key;  ///< Z85, 40 characters
};

/// A fresh key pair (zmq_curve_keypair). Throws CurveUnavailableError without CURVE.
CurveKeyPair make_curve_keypair();

struct CurveKeyFiles {
  std::string secret_file;  ///< PREFIX.key
  std::string public_file;  ///< PREFIX.pub
  std::string public_key;
};

/// Writes a fresh key pair to PREFIX.key and PREFIX.pub. Existing files are an InputError
/// (naming them and the fix) unless `overwrite`. Throws CurveUnavailableError, InputError (a
/// file that cannot be written).
CurveKeyFiles write_curve_keypair(const std::string& prefix, bool overwrite);

}  // namespace crashlink::transport
