#include "facecap/expr/emotions.hpp"

#include <algorithm>
#include <cctype>

#include <map>

namespace facecap {

namespace {

using Prototype = std::vector<std::pair<std::string, double>>;

Prototype both(std::initializer_list<std::pair<std::string, double>> shapes) {
  Prototype p;
  for (const auto& [name, w] : shapes) {
    if (name.ends_with("_")) {
      p.emplace_back(name + "L", w);
      p.emplace_back(name + "R", w);
    } else {
      p.emplace_back(name, w);
    }
  }
  return p;
}

const std::map<Emotion, Prototype>& prototypes() {
  static const std::map<Emotion, Prototype> table = {
      {Emotion::kNeutral, {}},
      {Emotion::kHappiness, both({{"cheekSquint_", 0.6}, {"mouthSmile_", 1.0}, {"eyeSquint_", 0.3}})},
      {Emotion::kSadness,
       both({{"browInnerUp_", 1.0}, {"browDown_", 0.4}, {"mouthFrown_", 0.9}, {"mouthShrugLower", 0.3}})},
      {Emotion::kSurprise, both({{"browInnerUp_", 1.0}, {"browOuterUp_", 1.0}, {"eyeWide_", 0.8}, {"jawOpen", 0.4}})},
      {Emotion::kFear, both({{"browInnerUp_", 1.0},
                             {"browOuterUp_", 0.6},
                             {"browDown_", 0.4},
                             {"eyeWide_", 0.9},
                             {"eyeSquint_", 0.3},
                             {"mouthStretch_", 0.9},
                             {"jawOpen", 0.25}})},
      {Emotion::kAnger,
       both({{"browDown_", 1.0}, {"eyeWide_", 0.3}, {"eyeSquint_", 0.6}, {"mouthPress_", 0.8}, {"noseSneer_", 0.3}})},
      {Emotion::kDisgust, both({{"noseSneer_", 1.0},
                                {"mouthUpperUp_", 0.6},
                                {"mouthFrown_", 0.5},
                                {"mouthLowerDown_", 0.4},
                                {"browDown_", 0.3}})},
  };
  return table;
}

}  // namespace

const char* to_string(Emotion e) {
  switch (e) {
    case Emotion::kNeutral:
      return "neutral";
    case Emotion::kAnger:
      return "anger";
    case Emotion::kDisgust:
      return "disgust";
    case Emotion::kFear:
      return "fear";
    case Emotion::kHappiness:
      return "happiness";
    case Emotion::kSadness:
      return "sadness";
    case Emotion::kSurprise:
      return "surprise";
  }
  return "neutral";
}

std::optional<Emotion> parse_emotion(const std::string& name) {
  std::string lower = name;  // "Happiness" and "happiness" alike
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (Emotion e : {Emotion::kNeutral, Emotion::kAnger, Emotion::kDisgust, Emotion::kFear, Emotion::kHappiness,
                    Emotion::kSadness, Emotion::kSurprise}) {
    if (lower == to_string(e)) return e;
  }
  static const std::pair<const char*, Emotion> kAdjectives[] = {
      {"happy", Emotion::kHappiness},   {"sad", Emotion::kSadness}, {"angry", Emotion::kAnger},
      {"afraid", Emotion::kFear},       {"scared", Emotion::kFear}, {"disgusted", Emotion::kDisgust},
      {"surprised", Emotion::kSurprise}};
  for (const auto& [adjective, e] : kAdjectives)
    if (lower == adjective) return e;
  return std::nullopt;
}

const char* emotion_choices() {
  return "neutral, anger, disgust, fear, happiness, sadness, surprise (or happy, sad, angry, afraid, disgusted, "
         "surprised)";
}

const std::vector<Emotion>& all_emotions() {
  static const std::vector<Emotion> e = {Emotion::kAnger,     Emotion::kDisgust, Emotion::kFear,
                                         Emotion::kHappiness, Emotion::kSadness, Emotion::kSurprise};
  return e;
}

const std::vector<std::pair<std::string, double>>& emotion_prototype(Emotion e) { return prototypes().at(e); }

std::vector<std::string> defining_shapes(Emotion e) {
  std::vector<std::string> out;
  for (const auto& [name, w] : emotion_prototype(e))
    if (w >= 0.8 && name != "jawOpen") out.push_back(name);
  return out;
}

}  // namespace facecap
