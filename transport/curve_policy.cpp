#include "transport/curve_policy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string_view>

#include "transport/curve_errors.h"
#include "transport/curve_key.h"

namespace crashlink::transport {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_loopback_host(std::string_view host) {
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  const std::string h = lower(host);
  if (h == "localhost" || h == "::1" || h == "0:0:0:0:0:0:0:1") return true;
  // 127.0.0.0/8 written as a dotted quad: "127." and then digits and dots only.
  return h.starts_with("127.") &&
         std::all_of(h.begin(), h.end(), [](char c) { return c == '.' || (c >= '0' && c <= '9'); });
}

std::string reason(const Endpoint& endpoint) {
  if (!is_local_endpoint(endpoint)) {
    return fmt::format("CURVE is required on '{}', which is not a loopback or ipc endpoint",
                       endpoint.address);
  }
  return "CURVE was asked for (--curve)";
}

[[noreturn]] void missing(const Endpoint& endpoint, std::string_view what, std::string_view flag,
                          std::string_view env, std::string_view make) {
  throw CurveConfigError(endpoint.text,
                         fmt::format("{} and {} is not given; fix: pass {} FILE or set {}=FILE; {}",
                                     reason(endpoint), what, flag, env, make));
}

constexpr std::string_view kMakeSecret =
    "make a key pair with `crashlink keygen --out PREFIX` (PREFIX.key is the secret key)";

}  // namespace

bool is_local_endpoint(const Endpoint& endpoint) {
  switch (endpoint.scheme) {
    case Scheme::ipc:
    case Scheme::inproc:
      return true;
    case Scheme::tcp: {
      std::string_view address = endpoint.address;
      // ZeroMQ's "source;destination" form: the destination decides.
      if (const auto semi = address.find(';'); semi != std::string_view::npos) {
        address = address.substr(semi + 1);
      }
      const auto colon = address.rfind(':');
      return colon != std::string_view::npos && is_loopback_host(address.substr(0, colon));
    }
  }
  return false;
}

bool curve_on(const Endpoint& endpoint, const CurveOptions& options) {
  if (endpoint.scheme == Scheme::inproc) return false;
  return options.force || !is_local_endpoint(endpoint);
}

std::optional<CurveServerKeys> curve_server_keys(const Endpoint& endpoint,
                                                 const CurveOptions& options) {
  if (!curve_on(endpoint, options)) return std::nullopt;
  if (options.secret_key_file.empty()) {
    missing(endpoint, "the coordinator's secret key", "--curve-secret-key", kCurveSecretKeyEnv,
            kMakeSecret);
  }
  if (options.authorized_keys_file.empty() && !options.authorize_later) {
    missing(endpoint, "the file of the daemons' authorized public keys", "--curve-authorized-keys",
            kCurveAuthorizedKeysEnv, "put every daemon's PREFIX.pub in it, one key per line");
  }
  CurveServerKeys k;
  k.secret_key = read_curve_key_file(options.secret_key_file, "secret key", true);
  k.public_key = curve_public_key(k.secret_key);
  if (options.authorize_later) {
    k.authorized_file = "the partners' keys in the coordinator's Setup";
    k.authorize_later = true;
  } else {
    k.authorized = read_authorized_keys(options.authorized_keys_file);
    k.authorized_file = options.authorized_keys_file;
  }
  return k;
}

std::optional<CurveClientKeys> curve_client_keys(const Endpoint& endpoint,
                                                 const CurveOptions& options) {
  if (!curve_on(endpoint, options)) return std::nullopt;
  if (options.secret_key_file.empty()) {
    missing(endpoint, "this daemon's secret key", "--curve-secret-key", kCurveSecretKeyEnv,
            kMakeSecret);
  }
  if (options.server_key_file.empty() && options.server_key.empty()) {
    missing(endpoint, "the coordinator's public key", "--curve-server-key", kCurveServerKeyEnv,
            "it is the coordinator's PREFIX.pub");
  }
  CurveClientKeys k;
  k.secret_key = read_curve_key_file(options.secret_key_file, "secret key", true);
  k.public_key = curve_public_key(k.secret_key);
  k.server_key = !options.server_key.empty()
                     ? options.server_key
                     : read_curve_key_file(options.server_key_file, "server public key", false);
  return k;
}

}  // namespace crashlink::transport
