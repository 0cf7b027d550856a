#include "facecap/io/input_damage.hpp"

namespace facecap {

std::string damaged_frames_note(int damaged, const std::string& what) {
  if (damaged == 0) return "";
  return std::to_string(damaged) + " frame(s) of " + what +
         " were decoded with damage (a corrupt stream: parts of them, and of the frames predicted from them, are "
         "made up by the decoder)";
}

std::string refused_packets_note(int refused, const std::string& what) {
  if (refused == 0) return "";
  return "the decoder refused " + std::to_string(refused) + " packet(s) of " + what +
         " (a corrupt stream: their frames are lost; the frames' times, not their numbers, keep the gap)";
}

std::string early_end_note(const std::string& early_end, const std::string& what) {
  return early_end.empty() ? "" : what + " ends early: " + early_end;
}

std::vector<std::string> input_damage_notes(const InputDamage& damage, const std::string& what) {
  std::vector<std::string> notes;
  for (std::string note : {damaged_frames_note(damage.damaged, what), refused_packets_note(damage.refused, what),
                           early_end_note(damage.early_end, what)}) {
    if (!note.empty()) notes.push_back(std::move(note));
  }
  return notes;
}

std::string input_damage_note(const InputDamage& damage, const std::string& what) {
  return joined_notes(input_damage_notes(damage, what));
}

std::string joined_notes(const std::vector<std::string>& notes) {
  std::string line;
  for (const std::string& note : notes) {
    if (!note.empty()) line += (line.empty() ? "" : "; ") + note;
  }
  return line;
}

}  // namespace facecap
