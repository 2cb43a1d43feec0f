#include "transport/endpoint.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "transport/errors.h"

namespace crashlink::transport {

namespace {

constexpr std::string_view kForms =
    "expected tcp://host:port, ipc://path or inproc://name (e.g. tcp://127.0.0.1:5555, "
    "tcp://127.0.0.1:* to bind an ephemeral port, ipc:///tmp/crashlink.sock, inproc://run)";

[[noreturn]] void invalid(std::string_view text, const std::string& why) {
  throw TransportError(std::string(text), fmt::format("invalid endpoint: {}; {}", why, kForms));
}

void check_tcp(std::string_view text, std::string_view address, Use use) {
  const auto colon = address.rfind(':');
  if (colon == std::string_view::npos) invalid(text, "tcp endpoint without ':port'");
  const std::string_view host = address.substr(0, colon);
  const std::string_view port = address.substr(colon + 1);
  if (host.empty()) invalid(text, "empty host");
  if (host.front() == '[' && host.back() != ']') invalid(text, "unterminated IPv6 '[address]'");
  if (host == "*" && use == Use::connect) {
    invalid(text, "a daemon connects to a host name or address, not '*'");
  }
  if (port == "*" || port == "0") {
    if (use == Use::connect) {
      invalid(text,
              "cannot connect to an ephemeral port '*': connect to the port the "
              "coordinator printed (Router::endpoint())");
    }
    return;
  }
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc{} || end != port.data() + port.size() || value == 0 ||
      value > 65535) {
    invalid(text, fmt::format("port '{}' is not 1-65535 or '*'", port));
  }
}

}  // namespace

bool Endpoint::ephemeral() const {
  return scheme == Scheme::tcp && (address.ends_with(":*") || address.ends_with(":0"));
}

std::string_view scheme_name(Scheme scheme) {
  switch (scheme) {
    case Scheme::tcp:
      return "tcp";
    case Scheme::ipc:
      return "ipc";
    case Scheme::inproc:
      return "inproc";
  }
  return "?";
}

Endpoint parse_endpoint(std::string_view text, Use use) {
  const auto sep = text.find("://");
  if (sep == std::string_view::npos) invalid(text, "no '://'");
  const std::string_view scheme = text.substr(0, sep);
  const std::string_view address = text.substr(sep + 3);
  Endpoint e;
  e.address = std::string(address);
  e.text = std::string(text);
  if (scheme == "tcp") {
    e.scheme = Scheme::tcp;
    check_tcp(text, address, use);
  } else if (scheme == "ipc") {
    e.scheme = Scheme::ipc;
    if (address.empty()) invalid(text, "empty ipc path");
    if (address.size() > kMaxIpcPath) {
      invalid(text, fmt::format("ipc path of {} bytes, the limit is {} (sun_path); use a shorter "
                                "directory, e.g. TMPDIR=/tmp",
                                address.size(), kMaxIpcPath));
    }
  } else if (scheme == "inproc") {
    e.scheme = Scheme::inproc;
    if (address.empty()) invalid(text, "empty inproc name");
  } else {
    invalid(text, fmt::format("unknown transport '{}'", scheme));
  }
  return e;
}

std::string local_endpoint(Scheme scheme, std::string_view tag) {
  static std::atomic<unsigned> counter{0};
  const unsigned n = counter.fetch_add(1);
  switch (scheme) {
    case Scheme::tcp:
      return "tcp://127.0.0.1:*";
    case Scheme::ipc: {
      std::error_code ec;
      std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
      if (ec) dir = "/tmp";
      return fmt::format("ipc://{}/crashlink-{}-{}-{}", dir.string(), ::getpid(), n, tag);
    }
    case Scheme::inproc:
      return fmt::format("inproc://crashlink-{}-{}", n, tag);
  }
  return {};
}

}  // namespace crashlink::transport
