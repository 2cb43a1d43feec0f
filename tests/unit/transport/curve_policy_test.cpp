// When CURVE is on (transport/curve_policy.h): every endpoint that is not loopback tcp, ipc or
// inproc needs keys, and a missing one is a CurveConfigError naming the endpoint, what is
// missing and the fix; on loopback it is on only when forced.
#include "transport/curve_policy.h"

#include <gtest/gtest.h>

#include <string>

#include "curve_test_support.h"
#include "transport/curve_errors.h"
#include "transport/dealer.h"
#include "transport/router.h"

namespace crashlink::transport::test {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool local(const std::string& text, Use use = Use::bind) {
  return is_local_endpoint(parse_endpoint(text, use));
}

TEST(CurvePolicy, LoopbackIpcAndInprocAreLocal) {
  EXPECT_TRUE(local("tcp://127.0.0.1:*"));
  EXPECT_TRUE(local("tcp://127.3.2.1:5555"));
  EXPECT_TRUE(local("tcp://localhost:5555"));
  EXPECT_TRUE(local("tcp://LocalHost:5555"));
  EXPECT_TRUE(local("tcp://[::1]:5555"));
  EXPECT_TRUE(local("ipc:///tmp/crashlink.sock"));
  EXPECT_TRUE(local("inproc://run"));
  EXPECT_TRUE(local("tcp://10.0.0.2;127.0.0.1:5555", Use::connect));
}

TEST(CurvePolicy, EverythingElseIsNot) {
  EXPECT_FALSE(local("tcp://0.0.0.0:*"));
  EXPECT_FALSE(local("tcp://*:5555"));
  EXPECT_FALSE(local("tcp://10.1.2.3:5555"));
  EXPECT_FALSE(local("tcp://coordinator:5555"));
  EXPECT_FALSE(local("tcp://127.0.0.1.example.com:5555"));
  EXPECT_FALSE(local("tcp://[::]:5555"));
  EXPECT_FALSE(local("tcp://eth0:5555"));
  EXPECT_FALSE(local("tcp://127.0.0.1;10.0.0.2:5555", Use::connect));
}

TEST(CurvePolicy, OnWhenNotLocalOrForcedNeverOnInproc) {
  CurveOptions off;
  CurveOptions forced;
  forced.force = true;
  const auto loopback = parse_endpoint("tcp://127.0.0.1:*", Use::bind);
  const auto any = parse_endpoint("tcp://0.0.0.0:*", Use::bind);
  const auto ipc = parse_endpoint("ipc:///tmp/x.sock", Use::bind);
  const auto inproc = parse_endpoint("inproc://x", Use::bind);
  EXPECT_FALSE(curve_on(loopback, off));
  EXPECT_TRUE(curve_on(loopback, forced));
  EXPECT_TRUE(curve_on(any, off));
  EXPECT_FALSE(curve_on(ipc, off));
  EXPECT_TRUE(curve_on(ipc, forced));
  EXPECT_FALSE(curve_on(inproc, forced));
}

/// The CurveConfigError of building `make`, or a failure.
template <class Make>
std::string config_error(Make make) {
  try {
    make();
  } catch (const CurveConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no CurveConfigError";
  return {};
}

TEST(CurvePolicy, NonLoopbackBindWithoutKeysIsATypedError) {
  const std::string e = config_error([] { Router r("tcp://0.0.0.0:*"); });
  EXPECT_TRUE(has(e,
                  "transport tcp://0.0.0.0:*: CURVE is required on '0.0.0.0:*', which is not "
                  "a loopback or ipc endpoint"))
      << e;
  EXPECT_TRUE(has(e, "the coordinator's secret key is not given")) << e;
  EXPECT_TRUE(has(e, "--curve-secret-key FILE or set CRASHLINK_CURVE_SECRET_KEY_FILE=FILE")) << e;
  EXPECT_TRUE(has(e, "crashlink keygen --out PREFIX")) << e;

  const KeyDir dir;
  SocketOptions o;
  o.curve.secret_key_file = dir.pair("coordinator").secret_file;
  const std::string e2 = config_error([&] { Router r("tcp://*:*", o); });
  EXPECT_TRUE(has(e2, "the file of the daemons' authorized public keys is not given")) << e2;
  EXPECT_TRUE(has(e2, "--curve-authorized-keys FILE or set CRASHLINK_CURVE_AUTHORIZED_KEYS_FILE"))
      << e2;
}

TEST(CurvePolicy, NonLoopbackConnectWithoutKeysIsATypedError) {
  // 192.0.2.0/24 is TEST-NET-1: never reached, the error comes before any connection.
  const std::string e = config_error([] { Dealer d("tcp://192.0.2.7:5555", "wiper"); });
  EXPECT_TRUE(has(e, "transport tcp://192.0.2.7:5555: CURVE is required")) << e;
  EXPECT_TRUE(has(e, "this daemon's secret key is not given")) << e;

  const KeyDir dir;
  SocketOptions o;
  o.curve.secret_key_file = dir.pair("wiper").secret_file;
  const std::string e2 = config_error([&] { Dealer d("tcp://coordinator:5555", "wiper", o); });
  EXPECT_TRUE(has(e2, "the coordinator's public key is not given")) << e2;
  EXPECT_TRUE(has(e2, "--curve-server-key FILE or set CRASHLINK_CURVE_SERVER_KEY_FILE")) << e2;
  EXPECT_TRUE(has(e2, "the coordinator's PREFIX.pub")) << e2;
}

TEST(CurvePolicy, ForcedOnLoopbackWithoutKeysSaysItWasAskedFor) {
  SocketOptions o;
  o.curve.force = true;
  const std::string e = config_error([&] { Router r("tcp://127.0.0.1:*", o); });
  EXPECT_TRUE(has(e, "CURVE was asked for (--curve) and the coordinator's secret key is not given"))
      << e;
}

TEST(CurvePolicy, BadKeyFileIsAKeyFileErrorWithFileAndLine) {
  const KeyDir dir;
  SocketOptions o;
  o.curve.force = true;
  o.curve.secret_key_file = dir.write("bad.key", "# secret\nnot-a-key\n");
  o.curve.server_key_file = dir.pair("coordinator").public_file;
  try {
    Dealer d("tcp://127.0.0.1:5555", "wiper", o);
    ADD_FAILURE() << "a bad secret key file was accepted";
  } catch (const CurveKeyFileError& e) {
    EXPECT_EQ(e.file(), o.curve.secret_key_file);
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(CurvePolicy, LoopbackWithoutForceNeedsNoKeys) {
  Router r("tcp://127.0.0.1:*");
  EXPECT_FALSE(r.curve());
  Dealer d(r.endpoint(), "wiper");
  EXPECT_FALSE(d.curve());
}

}  // namespace
}  // namespace crashlink::transport::test
