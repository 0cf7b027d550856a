#pragma once
// What a corrupt video cost a run that read it: frames decoded with their
// damage concealed, packets the decoder refused outright (their frames lost
// without a trace in the frame numbers), and an end short of the one its
// container declares. The user is told each in a line naming the input.
#include <string>
#include <vector>

namespace facecap {

struct InputDamage {
  int damaged = 0;        // frames decoded with damage concealed (Frame::damaged)
  int refused = 0;        // packets the decoder refused (FrameSource::refused_packets): their frames are lost
  std::string early_end;  // why the input ended short of its declared end (FrameSource::early_end), or ""

  bool any() const { return damaged > 0 || refused > 0 || !early_end.empty(); }
};

// "N frame(s) of WHAT were decoded with damage (...)", "" where `damaged` is 0.
std::string damaged_frames_note(int damaged, const std::string& what);
// "the decoder refused N packet(s) of WHAT (...)", "" where `refused` is 0.
std::string refused_packets_note(int refused, const std::string& what);
// "WHAT ends early: REASON" (FrameSource::early_end), "" where `early_end` is "".
std::string early_end_note(const std::string& early_end, const std::string& what);
// The three notes above that are not empty, in that order.
std::vector<std::string> input_damage_notes(const InputDamage& damage, const std::string& what);
// The same in one line, "; " between; "" where the input had no damage.
std::string input_damage_note(const InputDamage& damage, const std::string& what);
// The notes that are not empty, "; " between.
std::string joined_notes(const std::vector<std::string>& notes);

}  // namespace facecap
