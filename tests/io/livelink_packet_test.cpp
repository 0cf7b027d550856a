#include "facecap/io/livelink_packet.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"
#include "facecap/io/udp_sender.hpp"
#include "io/livelink_receiver.hpp"

namespace facecap {

// The app's version-6 datagram, byte for byte, written out by hand from its
// layout: big-endian lengths, frame time and floats.
TEST(LiveLinkPacket, LaysOutTheAppsVersion6Datagram) {
  LiveLinkFace::Values values{};
  values[0] = 1.0f;    // EyeBlinkLeft
  values[60] = -2.0f;  // RightEyeRoll
  LiveLinkFrameTime time;
  time.frame = 0x01020304;
  time.sub_frame = 0.5f;
  time.rate_numerator = 30;
  time.rate_denominator = 1;
  std::vector<uint8_t> want = {6,  0,    0,    0, 1,    'd', 0, 0, 0, 2, 'a', 'b',  // version, device id, subject
                               1,  2,    3,    4, 0x3F, 0,   0, 0, 0, 0, 0,   30,  0, 0, 0, 1,  // frame time
                               61, 0x3F, 0x80, 0, 0};                                           // count, EyeBlinkLeft
  want.resize(want.size() + 59 * 4, 0);
  for (const uint8_t b : {0xC0, 0, 0, 0}) want.push_back(b);
  EXPECT_EQ(livelink_packet("d", "ab", time, values), want);
  // 284 bytes with facecap's names, as the stream sends them.
  EXPECT_EQ(livelink_packet("facecap", "facecap", time, values).size(), 284u);
}

TEST(LiveLinkPacket, FrameTimesCountFramesAtTheInputsRate) {
  const LiveLinkFrameTime t = LiveLinkFrameTime::at(3661.5, 25);
  EXPECT_EQ(t.frame, 91537);
  EXPECT_FLOAT_EQ(t.sub_frame, 0.5f);
  EXPECT_EQ(t.rate_numerator, 25);
  EXPECT_EQ(t.rate_denominator, 1);
  const LiveLinkFrameTime ntsc = LiveLinkFrameTime::at(1001.0, 30000.0 / 1001.0);
  EXPECT_EQ(ntsc.rate_numerator, 30000);
  EXPECT_EQ(ntsc.rate_denominator, 1001);
  EXPECT_EQ(ntsc.frame, 30000);
  const LiveLinkFrameTime film = LiveLinkFrameTime::at(0, 24000.0 / 1001.0);
  EXPECT_EQ(film.rate_numerator, 24000);
  EXPECT_EQ(film.rate_denominator, 1001);
  const LiveLinkFrameTime odd = LiveLinkFrameTime::at(2.0, 12.5);
  EXPECT_EQ(odd.rate_numerator, 25);
  EXPECT_EQ(odd.rate_denominator, 2);
  EXPECT_EQ(odd.frame, 25);
  EXPECT_EQ(LiveLinkFrameTime::at(1.0, 0).rate_numerator, 30);  // an unknown rate
}

TEST(UdpSender, ParsesHostAndPort) {
  NetworkTarget t = parse_network_target("studio-pc", 11111, "--x");
  EXPECT_EQ(t.host, "studio-pc");
  EXPECT_EQ(t.port, 11111);
  t = parse_network_target("10.0.0.7:9000", 11111, "--x");
  EXPECT_EQ(t.host, "10.0.0.7");
  EXPECT_EQ(t.port, 9000);
  t = parse_network_target("[::1]:9000", 11111, "--x");
  EXPECT_EQ(t.host, "::1");
  EXPECT_EQ(t.port, 9000);
  t = parse_network_target("::1", 11111, "--x");
  EXPECT_EQ(t.host, "::1");
  EXPECT_EQ(t.port, 11111);
  for (const char* bad : {"", ":9000", "host:", "host:0", "host:70000", "host:12ab", "[::1", "[::1]9000"})
    EXPECT_THROW(parse_network_target(bad, 11111, "--x"), Error) << bad;
  EXPECT_THROW(UdpSender({"no-such-host.invalid", 11111}), Error);
}

// A datagram sent reaches a socket listening on the loopback, whole.
TEST(UdpSender, SendsDatagramsToTheTarget) {
  const test::UdpReceiver receiver;
  UdpSender sender({"127.0.0.1", receiver.port()});
  EXPECT_EQ(sender.address(), "127.0.0.1:" + std::to_string(receiver.port()));
  LiveLinkFace::Values values{};
  values[17] = 0.25f;  // JawOpen
  const std::vector<uint8_t> packet = livelink_packet("facecap", "me", LiveLinkFrameTime::at(10, 30), values);
  ASSERT_TRUE(sender.send(packet)) << sender.last_error();
  const auto got = receiver.receive();
  ASSERT_TRUE(got);
  EXPECT_EQ(*got, packet);
  const test::LiveLinkDatagram d = test::decode_livelink(*got);
  EXPECT_EQ(d.version, 6);
  EXPECT_EQ(d.subject, "me");
  EXPECT_EQ(d.frame, 300);
  ASSERT_EQ(d.values.size(), 61u);
  EXPECT_EQ(d.values[17], 0.25f);
}

}  // namespace facecap
