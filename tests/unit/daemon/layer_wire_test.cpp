// The layer vectors on the wire (solver/daemon/layer_wire.h): every field of a LayerMessage
// survives the round trip through wire::Envelope, flags included (`last` ends a variable run,
// `pause` makes a holder checkpoint with its owner: a flag lost on the wire would let a chain of
// daemons pause at different instants).
#include "solver/daemon/layer_wire.h"

#include <gtest/gtest.h>

using namespace crashlink;

TEST(LayerWire, EveryFieldOfBothKindsSurvivesTheRoundTrip) {
  for (const bool flag : {false, true}) {
    cosim::LayerMessage d;
    d.kind = cosim::LayerMessage::Kind::Displacement;
    d.interface_index = 3;
    d.time = 123456789012345;
    d.first = {1.0, -2.5, 3e-9};
    d.second = {0.1, 0.2, 0.3};
    d.last = flag;
    d.pause = !flag;
    const auto back = daemon::to_layer_message(daemon::to_envelope(d));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->kind, d.kind);
    EXPECT_EQ(back->interface_index, d.interface_index);
    EXPECT_EQ(back->time, d.time);
    EXPECT_EQ(back->first, d.first);
    EXPECT_EQ(back->second, d.second);
    EXPECT_EQ(back->last, d.last);
    EXPECT_EQ(back->pause, d.pause);

    cosim::LayerMessage f;
    f.kind = cosim::LayerMessage::Kind::Force;
    f.interface_index = 1;
    f.time = flag ? 0 : 77;
    f.first = {4.0, 5.0, 6.0};
    f.proposal = flag ? 0 : 4242;
    const auto fb = daemon::to_layer_message(daemon::to_envelope(f));
    ASSERT_TRUE(fb.has_value());
    EXPECT_EQ(fb->kind, f.kind);
    EXPECT_EQ(fb->time, f.time);
    EXPECT_EQ(fb->first, f.first);
    EXPECT_TRUE(fb->second.empty());
    EXPECT_EQ(fb->proposal, f.proposal);
  }
  EXPECT_FALSE(daemon::to_layer_message(wire::Envelope()).has_value());
}
