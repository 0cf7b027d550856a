#include "facecap/io/livelink_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "facecap/core/csv_line.hpp"

namespace facecap {

TEST(LiveLinkCsv, TimecodesCountFramesWithinEachSecond) {
  EXPECT_EQ(LiveLinkCsv::timecode(0.0, 30), "00:00:00:00.000");
  EXPECT_EQ(LiveLinkCsv::timecode(1.0 / 30, 30), "00:00:00:01.000");
  EXPECT_EQ(LiveLinkCsv::timecode(59.0 / 30, 30), "00:00:01:29.000");
  EXPECT_EQ(LiveLinkCsv::timecode(3661.5, 25), "01:01:01:12.500");  // half a frame in
  EXPECT_EQ(LiveLinkCsv::timecode(-1.0, 30), "00:00:00:00.000");
}

// The model's names map onto ARKit's: sided shapes by their suffix, shapes
// of their own by name, ARKit shapes the model splits as the mean of the
// halves, and one it lacks as 0; angles in radians.
TEST(LiveLinkCsv, MapsTheModelsWeightsOntoArkitsColumns) {
  const std::vector<std::string> names = {"eyeBlink_L",    "eyeBlink_R",    "jawLeft",
                                          "browInnerUp_L", "browInnerUp_R", "mouthSmile_L"};
  const LiveLinkFace face(names);
  const LiveLinkCsv csv(30);
  const std::vector<std::string> header = split_csv_line(csv.header());
  ASSERT_EQ(header.size(), 63u);
  EXPECT_EQ(header[0], "Timecode");
  EXPECT_EQ(header[1], "BlendShapeCount");
  EXPECT_EQ(header[62], "RightEyeRoll");
  Eigen::VectorXf w(6);
  w << 0.1f, 0.2f, 0.3f, 0.4f, 0.8f, 0.5f;
  LiveLinkPose pose;
  pose.head_yaw_pitch_roll_deg = {90, -45, 0};
  pose.left_eye_deg = {10, 0};
  pose.right_eye_deg = {-20, 5};
  const std::vector<std::string> row = split_csv_line(csv.row(2.0, face.values(w, pose)));
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(row[1], "61");
  auto value = [&](const std::string& column) {
    for (size_t k = 0; k < header.size(); ++k)
      if (header[k] == column) return std::stod(row[k]);
    ADD_FAILURE() << column;
    return -1.0;
  };
  EXPECT_NEAR(value("EyeBlinkLeft"), 0.1, 1e-6);
  EXPECT_NEAR(value("EyeBlinkRight"), 0.2, 1e-6);
  EXPECT_NEAR(value("JawLeft"), 0.3, 1e-6);
  EXPECT_NEAR(value("JawRight"), 0.0, 1e-9);  // not in this model
  EXPECT_NEAR(value("BrowInnerUp"), 0.6, 1e-6);
  EXPECT_NEAR(value("MouthSmileLeft"), 0.5, 1e-6);
  EXPECT_NEAR(value("TongueOut"), 0.0, 1e-9);
  EXPECT_NEAR(value("HeadYaw"), 1.5707963, 1e-6);
  EXPECT_NEAR(value("HeadPitch"), -0.7853982, 1e-6);
  EXPECT_NEAR(value("LeftEyeYaw"), 0.1745329, 1e-6);
  EXPECT_NEAR(value("RightEyeYaw"), -0.3490659, 1e-6);
  EXPECT_NEAR(value("RightEyePitch"), 0.0872665, 1e-6);
  // The take's columns are the app's: JawRight before JawLeft, as the stream
  // (Unreal's EARFaceBlendShape) has them the other way round.
  EXPECT_EQ(header[2 + 15], "JawRight");
  EXPECT_EQ(LiveLinkFace::names()[15], "JawLeft");
  EXPECT_EQ(header[2 + 21], "MouthRight");
  EXPECT_EQ(LiveLinkFace::names()[21], "MouthLeft");
}

// Values that are not numbers reach no output as such.
TEST(LiveLinkFace, NonFiniteValuesAreZero) {
  const LiveLinkFace face({"jawOpen"});
  Eigen::VectorXf w(1);
  w << std::nanf("");
  LiveLinkPose pose;
  pose.head_yaw_pitch_roll_deg.x() = std::numeric_limits<double>::infinity();
  const LiveLinkFace::Values v = face.values(w, pose);
  EXPECT_EQ(v[LiveLinkFace::index_of("JawOpen")], 0.0f);
  EXPECT_EQ(v[LiveLinkFace::index_of("HeadYaw")], 0.0f);
  EXPECT_EQ(LiveLinkFace::index_of("Nothing"), -1);
}

}  // namespace facecap
