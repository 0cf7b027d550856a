#include "facecap/expr/emotions.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_support.hpp"

namespace facecap {

TEST(Emotions, NamesRoundTripAndUnknownIsRejected) {
  for (Emotion e : all_emotions()) EXPECT_EQ(parse_emotion(to_string(e)), e);
  EXPECT_EQ(parse_emotion("neutral"), Emotion::kNeutral);
  EXPECT_EQ(parse_emotion("Happiness"), Emotion::kHappiness);
  EXPECT_FALSE(parse_emotion("contempt").has_value());
  EXPECT_EQ(all_emotions().size(), 6u);
}

TEST(Emotions, AdjectivesNameTheirEmotion) {
  EXPECT_EQ(parse_emotion("happy"), Emotion::kHappiness);
  EXPECT_EQ(parse_emotion("Sad"), Emotion::kSadness);
  EXPECT_EQ(parse_emotion("angry"), Emotion::kAnger);
  EXPECT_EQ(parse_emotion("afraid"), Emotion::kFear);
  EXPECT_EQ(parse_emotion("scared"), Emotion::kFear);
  EXPECT_EQ(parse_emotion("disgusted"), Emotion::kDisgust);
  EXPECT_EQ(parse_emotion("SURPRISED"), Emotion::kSurprise);
  EXPECT_FALSE(parse_emotion("happ").has_value());
  // The choices an error message lists are all taken.
  const std::string choices = emotion_choices();
  for (const char* name : {"happiness", "happy", "surprised", "neutral"})
    EXPECT_NE(choices.find(name), std::string::npos) << name;
}

TEST(Emotions, HappinessIsDefinedByTheSmile) {
  auto shapes = defining_shapes(Emotion::kHappiness);
  std::sort(shapes.begin(), shapes.end());
  EXPECT_EQ(shapes, (std::vector<std::string>{"mouthSmile_L", "mouthSmile_R"}));
  for (Emotion e : all_emotions()) EXPECT_FALSE(defining_shapes(e).empty()) << to_string(e);
}

TEST(Emotions, PrototypesNameShapesOfTheModel) {
  FACECAP_REQUIRE_MODEL(model);
  for (Emotion e : all_emotions()) {
    for (const auto& [name, weight] : emotion_prototype(e)) {
      EXPECT_NE(std::find(model->expression_names.begin(), model->expression_names.end(), name),
                model->expression_names.end())
          << to_string(e) << ": " << name;
      EXPECT_GT(weight, 0.0);
      EXPECT_LE(weight, 1.0);
    }
  }
}

}  // namespace facecap
