#pragma once
// Videos damaged part-way for the tests of corrupt input: two seconds of a
// clip (its stream copied, the index first), then the same with 32 bytes of
// 0xFF three quarters into the first video packet, its keyframe (`ffmpeg -f
// null` reports one corrupt frame in it; every frame still decodes), the
// same with its index damaged (one sample's size made absurd: libavformat
// indexes the samples before it and ends the stream there, as ffmpeg does),
// and the same with that sample's size 4 bytes short (every packet is read,
// but those after it in its chunk start 4 bytes early, and the decoder
// refuses them: `ffmpeg -f null` reports as many decode errors), and the same
// with its one chunk's offset 4 bytes on (every packet misread: none decodes).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "app/command.hpp"
#include "test_support.hpp"

namespace facecap::test {

struct DamagedClip {
  std::filesystem::path clean, damaged, damaged_index, misaligned, shifted;
  static constexpr int kFrames = 52;  // in `clean`, as its index lists (two seconds at 25 fps)
  // The sample whose size `damaged_index` and `misaligned` change, and so
  // the frames of `damaged_index` that can be read.
  static constexpr int kIndexDamagedAt = 20;
  // What FrameSource::early_end says of `damaged_index` once it has ended.
  static std::string damaged_index_early_end() {
    return "the last " + std::to_string(kFrames - kIndexDamagedAt) + " of the " + std::to_string(kFrames) +
           " frames its index lists could not be read (the file is cut short or its index damaged)";
  }
};

// Writes both clips into `dir`; throws std::runtime_error where ffmpeg or
// ffprobe fail.
inline DamagedClip write_damaged_clip(const std::filesystem::path& source, const std::filesystem::path& dir) {
  DamagedClip clip{dir / "clean.mp4", dir / "damaged.mp4", dir / "damaged_index.mp4", dir / "misaligned.mp4",
                   dir / "shifted.mp4"};
  const CommandResult made = run_command("ffmpeg -hide_banner -loglevel error -y -i " + source.string() +
                                         " -t 2 -c copy -movflags +faststart " + clip.clean.string() + " 2>&1");
  if (made.code != 0) throw std::runtime_error("ffmpeg: " + made.out);
  // Where the first video packet lies in the file: "size=N" and "pos=N" lines.
  const CommandResult packet = run_command(
      "ffprobe -v error -select_streams v -read_intervals %+#1 -show_entries packet=size,pos -of default=nw=1 " +
      clip.clean.string() + " 2>&1");
  const auto field = [&](const std::string& key) {
    const size_t at = packet.out.find(key + "=");
    return at == std::string::npos ? size_t(0) : size_t(std::stoull(packet.out.substr(at + key.size() + 1)));
  };
  const size_t size = field("size"), pos = field("pos");
  std::string bytes = read_file(clip.clean);
  if (packet.code != 0 || size < 1000 || pos + size > bytes.size())
    throw std::runtime_error("ffprobe gave no usable first packet: " + packet.out);
  std::string hit = bytes;
  hit.replace(pos + size * 3 / 4, 32, 32, '\xff');
  std::ofstream(clip.damaged, std::ios::binary) << hit;
  // The sample size box (the clip's only track): "stsz", version and flags,
  // a size for every sample (0: listed), the count, then a size each, big-endian.
  const size_t stsz = bytes.find("stsz");
  const auto u32 = [&](size_t at) {
    return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
           uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
  };
  if (stsz == std::string::npos || bytes.find("stsz", stsz + 1) != std::string::npos || u32(stsz + 8) != 0 ||
      u32(stsz + 12) != uint32_t(DamagedClip::kFrames))
    throw std::runtime_error("the clip's sample size box is not the one expected");
  const size_t entry = stsz + 16 + 4 * DamagedClip::kIndexDamagedAt;
  std::string misaligned = bytes;
  const auto put_u32 = [](std::string& to, size_t at, uint32_t value) {
    for (int k = 0; k < 4; ++k) to[at + k] = char(value >> (24 - 8 * k) & 0xff);
  };
  put_u32(misaligned, entry, u32(entry) - 4);
  std::ofstream(clip.misaligned, std::ios::binary) << misaligned;
  // The chunk offset box: "stco", version and flags, the count, an offset each.
  const size_t stco = bytes.find("stco");
  if (stco == std::string::npos || u32(stco + 8) != 1) throw std::runtime_error("the clip is not one chunk");
  std::string shifted = bytes;
  put_u32(shifted, stco + 12, u32(stco + 12) + 4);
  std::ofstream(clip.shifted, std::ios::binary) << shifted;
  put_u32(bytes, entry, 0x54000000);  // 1.4 GB
  std::ofstream(clip.damaged_index, std::ios::binary) << bytes;
  return clip;
}

// The frames of `video` that `ffprobe -count_frames` decodes: ground truth
// for how much of a damaged video can be read. Throws std::runtime_error
// where ffprobe fails.
inline int ffprobe_frames_decoded(const std::filesystem::path& video) {
  const CommandResult ffprobe =
      run_command("ffprobe -v quiet -count_frames -select_streams v -show_entries stream=nb_read_frames -of csv=p=0 " +
                  video.string());
  if (ffprobe.code != 0) throw std::runtime_error("ffprobe: " + ffprobe.out);
  return std::stoi(ffprobe.out);
}

}  // namespace facecap::test
