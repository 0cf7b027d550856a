#pragma once
// The seven expression domains of §5.2.3 and the facial action units that
// define each basic emotion (Ekman and Friesen's EMFACS prototypes), mapped
// to ICT/ARKit shapes with the table in FACTS.md:
//   happiness  AU6 + AU12                      cheek squint, smile
//   sadness    AU1 + AU4 + AU15                inner brow up, brow down, frown
//   surprise   AU1 + AU2 + AU5 + AU26          brows up, eyes wide, jaw drop
//   fear       AU1 + AU2 + AU4 + AU5 + AU7 + AU20 + AU26
//   anger      AU4 + AU5 + AU7 + AU23          brow down, eyes wide and tight, lips pressed
//   disgust    AU9 + AU10 + AU15 + AU16        nose wrinkle, upper lip up, frown, lower lip down
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace facecap {

enum class Emotion { kNeutral, kAnger, kDisgust, kFear, kHappiness, kSadness, kSurprise };

const char* to_string(Emotion e);
// The name (to_string's, any case) or its adjective: happy, sad, angry,
// afraid or scared, disgusted, surprised.
std::optional<Emotion> parse_emotion(const std::string& name);
// What parse_emotion takes, in words for an error message.
const char* emotion_choices();
const std::vector<Emotion>& all_emotions();  // the six besides neutral

// The prototype: ICT shape names with their relative activation.
const std::vector<std::pair<std::string, double>>& emotion_prototype(Emotion e);

// The shapes that define an emotion (prototype weight >= 0.8, jaw excluded):
// what `eval transform` expects to rise (for happiness mouthSmile_L/R).
std::vector<std::string> defining_shapes(Emotion e);

}  // namespace facecap
