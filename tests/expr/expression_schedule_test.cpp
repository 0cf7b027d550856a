#include "facecap/expr/expression_schedule.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {

namespace {

std::string error_of(const std::filesystem::path& p) {
  try {
    ExpressionSchedule::read(p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ExpressionSchedule, ReadsKeysAndInterpolatesBetweenThem) {
  TempDir dir;
  std::ofstream(dir.path() / "s.txt") << "# a comment\n0 neutral 0\n\n2 happiness 1\n4 sadness 0.5\n";
  const ExpressionSchedule s = ExpressionSchedule::read(dir.path() / "s.txt");
  ASSERT_EQ(s.keys().size(), 3u);
  const ScheduleState mid = s.at(1.0);
  EXPECT_EQ(mid.a.target, Emotion::kNeutral);
  EXPECT_EQ(mid.b.target, Emotion::kHappiness);
  EXPECT_NEAR(mid.b_share, 0.5, 1e-12);
  const ScheduleState late = s.at(3.5);
  EXPECT_EQ(late.a.target, Emotion::kHappiness);
  EXPECT_EQ(late.b.target, Emotion::kSadness);
  EXPECT_NEAR(late.b_share, 0.75, 1e-12);
  // Before the first and after the last key the schedule holds.
  EXPECT_EQ(s.at(-1).a.target, Emotion::kNeutral);
  EXPECT_NEAR(s.at(-1).b_share, 0.0, 1e-12);
  const ScheduleState after = s.at(10);
  EXPECT_EQ(after.b_share > 0.5 ? after.b.target : after.a.target, Emotion::kSadness);
}

TEST(ExpressionSchedule, ConstantHoldsEverywhere) {
  const ExpressionSchedule s = ExpressionSchedule::constant(Emotion::kSurprise, 0.4);
  for (double t : {0.0, 1.0, 100.0}) {
    const ScheduleState st = s.at(t);
    const ScheduleKey& k = st.b_share > 0.5 ? st.b : st.a;
    EXPECT_EQ(k.target, Emotion::kSurprise);
    EXPECT_DOUBLE_EQ(k.intensity, 0.4);
  }
}

TEST(ExpressionSchedule, MalformedFilesNameTheLine) {
  TempDir dir;
  std::ofstream(dir.path() / "words.txt") << "0 neutral 0\nsoon happiness 1\n";
  std::ofstream(dir.path() / "emotion.txt") << "0 neutral 0\n1 contempt 1\n";
  std::ofstream(dir.path() / "intensity.txt") << "0 happiness 1.5\n";
  std::ofstream(dir.path() / "empty.txt") << "# nothing\n";
  EXPECT_NE(error_of(dir.path() / "words.txt").find("line 2"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "emotion.txt").find("contempt"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "intensity.txt").find("line 1"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "empty.txt").find("no keys"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "missing.txt").find("not found"), std::string::npos);
}

}  // namespace facecap
