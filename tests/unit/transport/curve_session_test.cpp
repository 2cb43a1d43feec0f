// The session over CURVE (docs/processes.md, "Security (CURVE)"), forced on loopback tcp (an
// ephemeral port read back) and ipc: a daemon with the right keys completes the handshake and
// messages flow; a daemon whose key is not authorised, or that has the wrong server key, or that
// does not use CURVE at all, is refused: it fails with CurveRefusedError saying so, long before
// the handshake timeout, and the coordinator's notices name it. Every wait is bounded.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "curve_test_support.h"
#include "transport/curve_errors.h"
#include "transport/router.h"
#include "transport_test_support.h"

namespace crashlink::transport::test {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kHash = "c0ffee";

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class CurveSession : public ::testing::TestWithParam<Scheme> {
 protected:
  CurveSession() {
    coordinator_keys = keys.pair("coordinator");
    wiper_keys = keys.pair("wiper");
    body_keys = keys.pair("body");
    stranger_keys = keys.pair("stranger");
    authorized = keys.write("authorized", "# the run's daemons\n" + wiper_keys.public_key +
                                              "  # wiper\n" + body_keys.public_key + "  # body\n");
  }

  CoordinatorConfig config() const {
    CoordinatorConfig c;
    c.scenario_hash = kHash;
    c.domains = {"wiper", "body"};
    c.ticks_per_second = 1'000'000'000;
    c.options = fast_options();
    c.options.socket.curve.force = true;
    c.options.socket.curve.secret_key_file = coordinator_keys.secret_file;
    c.options.socket.curve.authorized_keys_file = authorized;
    return c;
  }

  /// A daemon's options: its secret key and the server key it believes in. The handshake
  /// timeout is long: a refusal must be seen from the handshake events, not from the timeout.
  static SessionOptions daemon_options(const CurveKeyFiles& own, const std::string& server_pub) {
    SessionOptions o = fast_options();
    o.handshake_timeout = 20s;
    o.socket.curve.force = true;
    o.socket.curve.secret_key_file = own.secret_file;
    o.socket.curve.server_key_file = server_pub;
    return o;
  }

  /// Connects `domain` with `options` and expects a CurveRefusedError; returns its text and how
  /// long the refusal took.
  std::pair<std::string, double> refused(CoordinatorLink& coordinator, const std::string& domain,
                                         const SessionOptions& options) {
    const auto t0 = Clock::now();
    try {
      (void)connect_daemon(coordinator, daemon_hello(domain, kHash), options);
      ADD_FAILURE() << "domain '" << domain << "' was accepted";
    } catch (const CurveRefusedError& e) {
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      return {e.what(), s};
    }
    return {};
  }

  /// The coordinator's notices until one contains `part` (polling up to 3 s).
  static std::string notice_with(CoordinatorLink& coordinator, const std::string& part) {
    std::string all;
    const auto deadline = Clock::now() + 3s;
    while (Clock::now() < deadline) {
      (void)coordinator.poll(10ms);
      for (const auto& n : coordinator.take_notices()) {
        all += n.text + "\n";
        if (has(n.text, part)) return n.text;
      }
    }
    ADD_FAILURE() << "no coordinator notice contains '" << part << "'; notices:\n" << all;
    return {};
  }

  std::string endpoint() const { return local_endpoint(GetParam(), "curve"); }

  KeyDir keys;
  CurveKeyFiles coordinator_keys, wiper_keys, body_keys, stranger_keys;
  std::string authorized;
};

TEST_P(CurveSession, AuthorisedDaemonsHandshakeAndExchange) {
  CoordinatorLink coordinator(endpoint(), config());
  if (GetParam() == Scheme::tcp) {
    EXPECT_TRUE(coordinator.endpoint().starts_with("tcp://127.0.0.1:")) << coordinator.endpoint();
  }
  DaemonLink wiper = connect_daemon(coordinator, daemon_hello("wiper", kHash),
                                    daemon_options(wiper_keys, coordinator_keys.public_file));
  DaemonLink body = connect_daemon(coordinator, daemon_hello("body", kHash),
                                   daemon_options(body_keys, coordinator_keys.public_file));
  EXPECT_TRUE(coordinator.all_joined());
  EXPECT_EQ(wiper.coordinator_hello().ticks_per_second(), 1'000'000'000);

  // Every kind of message, arrays of tricky doubles, both ways, bit for bit.
  const auto messages = every_kind(1000);
  for (const auto& m : messages) {
    if (m.has_hello() || m.has_heartbeat() || m.has_bye() || m.has_error()) continue;
    wiper.send(m);
    auto in = coordinator.poll(5s);
    ASSERT_TRUE(in.has_value());
    EXPECT_EQ(in->domain, "wiper");
    EXPECT_EQ(in->envelope.SerializeAsString(), m.SerializeAsString());
    coordinator.forward("body", *in);
    auto out = body.receive(5s);
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->SerializeAsString(), m.SerializeAsString());
  }
  EXPECT_TRUE(coordinator.take_notices().empty());
  wiper.bye("done");
  body.bye("done");
}

TEST_P(CurveSession, UnauthorisedKeyIsRefusedFastAndLogged) {
  CoordinatorLink coordinator(endpoint(), config());
  const auto [text, seconds] =
      refused(coordinator, "wiper", daemon_options(stranger_keys, coordinator_keys.public_file));
  std::printf("[measured] %s: unauthorised key refused after %.3f s (handshake timeout 20 s)\n",
              std::string(scheme_name(GetParam())).c_str(), seconds);
  EXPECT_LT(seconds, 2.0);
  EXPECT_TRUE(has(text, "the coordinator refused the connection of domain 'wiper'")) << text;
  EXPECT_TRUE(has(text, "refused this daemon's CURVE key (ZAP status 400)")) << text;
  EXPECT_TRUE(has(text, "public key " + stranger_keys.public_key +
                            " is not in the coordinator's "
                            "authorized keys file"))
      << text;
  EXPECT_TRUE(has(text, "--curve-authorized-keys")) << text;

  const std::string notice = notice_with(coordinator, stranger_keys.public_key);
  std::printf("[log] daemon: %s\n[log] coordinator notice: %s\n", text.c_str(), notice.c_str());
  EXPECT_TRUE(has(notice, "client public key " + stranger_keys.public_key +
                              " is not in the authorized keys file " + authorized + " (2 keys)"))
      << notice;
  if (GetParam() == Scheme::tcp) {
    EXPECT_TRUE(has(notice, "refused a CURVE connection from 127.0.0.1:")) << notice;
  } else {
    EXPECT_TRUE(has(notice, fmt::format("refused a CURVE connection from the local process {} "
                                        "(uid {}, gid {}):",
                                        ::getpid(), ::getuid(), ::getgid())))
        << notice;
  }
  EXPECT_FALSE(coordinator.joined("wiper"));
  // The authorised daemon still joins afterwards.
  DaemonLink wiper = connect_daemon(coordinator, daemon_hello("wiper", kHash),
                                    daemon_options(wiper_keys, coordinator_keys.public_file));
  EXPECT_TRUE(coordinator.joined("wiper"));
}

TEST_P(CurveSession, WrongServerKeyIsRefusedFastAndLogged) {
  CoordinatorLink coordinator(endpoint(), config());
  // The daemon believes the server is `stranger`: the coordinator cannot open its HELLO.
  const auto [text, seconds] =
      refused(coordinator, "body", daemon_options(body_keys, stranger_keys.public_file));
  std::printf("[measured] %s: wrong server key refused after %.3f s (handshake timeout 20 s)\n",
              std::string(scheme_name(GetParam())).c_str(), seconds);
  EXPECT_LT(seconds, 3.0);
  EXPECT_TRUE(has(text, "the coordinator refused the connection of domain 'body'")) << text;
  EXPECT_TRUE(has(text, "the server public key given to this daemon (" + stranger_keys.public_key +
                            ") is not the coordinator's"))
      << text;
  EXPECT_TRUE(has(text, "--curve-server-key")) << text;
  const std::string notice = notice_with(coordinator, "wrong server public key");
  std::printf("[log] daemon: %s\n[log] coordinator notice: %s\n", text.c_str(), notice.c_str());
  EXPECT_TRUE(has(notice, "ZMQ_PROTOCOL_ERROR_ZMTP_CRYPTOGRAPHIC")) << notice;
  EXPECT_TRUE(has(notice, coordinator_keys.public_key)) << notice;
  EXPECT_FALSE(coordinator.joined("body"));
}

TEST_P(CurveSession, DaemonWithoutCurveIsRefused) {
  CoordinatorLink coordinator(endpoint(), config());
  SessionOptions plain = fast_options();
  plain.handshake_timeout = 20s;
  const auto [text, seconds] = refused(coordinator, "wiper", plain);
  EXPECT_LT(seconds, 2.0);
  EXPECT_TRUE(has(text, "the coordinator requires CURVE and this daemon does not use it")) << text;
  EXPECT_TRUE(has(text, "--curve")) << text;
  const std::string notice = notice_with(coordinator, "does not use CURVE");
  EXPECT_TRUE(has(notice, "ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH")) << notice;
}

TEST_P(CurveSession, CurveDaemonAgainstPlainCoordinatorIsRefused) {
  CoordinatorConfig plain = config();
  plain.options.socket.curve = {};
  CoordinatorLink coordinator(endpoint(), plain);
  const auto [text, seconds] =
      refused(coordinator, "wiper", daemon_options(wiper_keys, coordinator_keys.public_file));
  EXPECT_LT(seconds, 2.0);
  EXPECT_TRUE(has(text, "this daemon uses CURVE and the coordinator does not")) << text;
}

INSTANTIATE_TEST_SUITE_P(Loopback, CurveSession, ::testing::Values(Scheme::tcp, Scheme::ipc),
                         scheme_test_name);

}  // namespace
}  // namespace crashlink::transport::test
