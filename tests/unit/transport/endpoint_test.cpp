// Endpoint strings (docs/design.md §3): the three transports, ephemeral ports, clear errors.
#include "transport/endpoint.h"

#include <gtest/gtest.h>

#include <string>

#include "transport/errors.h"

using crashlink::transport::local_endpoint;
using crashlink::transport::parse_endpoint;
using crashlink::transport::Scheme;
using crashlink::transport::TransportError;
using crashlink::transport::Use;

namespace {

std::string error_of(const std::string& text, Use use) {
  try {
    parse_endpoint(text, use);
  } catch (const TransportError& e) {
    EXPECT_EQ(e.endpoint(), text);
    return e.what();
  }
  ADD_FAILURE() << text << " was accepted";
  return {};
}

}  // namespace

TEST(Endpoint, ParsesTheThreeTransports) {
  const auto tcp = parse_endpoint("tcp://127.0.0.1:5555", Use::connect);
  EXPECT_EQ(tcp.scheme, Scheme::tcp);
  EXPECT_EQ(tcp.address, "127.0.0.1:5555");
  EXPECT_FALSE(tcp.ephemeral());
  EXPECT_TRUE(parse_endpoint("tcp://127.0.0.1:*", Use::bind).ephemeral());
  EXPECT_TRUE(parse_endpoint("tcp://*:0", Use::bind).ephemeral());
  EXPECT_EQ(parse_endpoint("tcp://[::1]:7000", Use::connect).address, "[::1]:7000");
  const auto ipc = parse_endpoint("ipc:///tmp/crashlink.sock", Use::bind);
  EXPECT_EQ(ipc.scheme, Scheme::ipc);
  EXPECT_EQ(ipc.address, "/tmp/crashlink.sock");
  const auto inproc = parse_endpoint("inproc://run", Use::connect);
  EXPECT_EQ(inproc.scheme, Scheme::inproc);
  EXPECT_EQ(inproc.text, "inproc://run");
}

TEST(Endpoint, RejectsWithTheReasonAndTheExpectedForm) {
  EXPECT_NE(error_of("127.0.0.1:5555", Use::connect).find("no '://'"), std::string::npos);
  EXPECT_NE(error_of("udp://127.0.0.1:5555", Use::bind).find("unknown transport 'udp'"),
            std::string::npos);
  EXPECT_NE(error_of("tcp://127.0.0.1", Use::bind).find("without ':port'"), std::string::npos);
  EXPECT_NE(error_of("tcp://127.0.0.1:70000", Use::bind).find("port '70000'"), std::string::npos);
  EXPECT_NE(error_of("tcp://127.0.0.1:x1", Use::bind).find("port 'x1'"), std::string::npos);
  EXPECT_NE(error_of("tcp://:5555", Use::bind).find("empty host"), std::string::npos);
  EXPECT_NE(error_of("tcp://127.0.0.1:*", Use::connect).find("ephemeral"), std::string::npos);
  EXPECT_NE(error_of("tcp://*:5555", Use::connect).find("not '*'"), std::string::npos);
  EXPECT_NE(error_of("ipc://", Use::bind).find("empty ipc path"), std::string::npos);
  EXPECT_NE(error_of("ipc:///" + std::string(200, 'a'), Use::bind).find("limit is 107"),
            std::string::npos);
  EXPECT_NE(error_of("inproc://", Use::connect).find("empty inproc name"), std::string::npos);
  // Every message shows the accepted forms.
  EXPECT_NE(error_of("zmq", Use::bind).find("expected tcp://host:port"), std::string::npos);
}

TEST(Endpoint, LocalEndpointsAreUniqueAndValid) {
  EXPECT_EQ(local_endpoint(Scheme::tcp), "tcp://127.0.0.1:*");
  const auto a = local_endpoint(Scheme::ipc, "t");
  const auto b = local_endpoint(Scheme::ipc, "t");
  EXPECT_NE(a, b);
  EXPECT_NO_THROW(parse_endpoint(a, Use::bind));
  EXPECT_NE(local_endpoint(Scheme::inproc), local_endpoint(Scheme::inproc));
  EXPECT_NO_THROW(parse_endpoint(local_endpoint(Scheme::inproc), Use::connect));
}
