#pragma once
// One frame of Live Link Face's UDP stream: the datagram Epic's iPhone app
// sends, and Unreal's Live Link source for it (Apple ARKit Face Support,
// port 11111 by default) reads into a subject's 61 curves (MetaHuman faces
// are driven by them). Version 6 of the packet, every field in network byte
// order (big-endian):
//   uint8  packet version, 6
//   int32  length, then that many bytes: the device id
//   int32  length, then that many bytes: the subject name
//   int32  frame number, float sub-frame,
//   int32  rate numerator, int32 rate denominator  (Unreal's FQualifiedFrameTime)
//   uint8  61, then 61 float: LiveLinkFace::Values, in its order
// The layout is the one public senders (PyLiveLinkFace and the tools built
// on it) and receivers agree on; no Unreal was at hand to check it against.
#include <cstdint>
#include <string_view>
#include <vector>

#include "facecap/io/livelink_face.hpp"

namespace facecap {

struct LiveLinkFrameTime {
  int32_t frame = 0;    // frames since midnight at the rate (a timecode, as the app sends)
  float sub_frame = 0;  // the part of a frame, [0, 1)
  int32_t rate_numerator = 30;
  int32_t rate_denominator = 1;

  // `seconds` (since midnight, say) at `fps` frames a second: 23.976, 29.97
  // and 59.94 are N*1000/1001, other rates to a thousandth of a frame a second.
  static LiveLinkFrameTime at(double seconds, double fps);
};

std::vector<uint8_t> livelink_packet(std::string_view device_id, std::string_view subject,
                                     const LiveLinkFrameTime& time, const LiveLinkFace::Values& values);

}  // namespace facecap
