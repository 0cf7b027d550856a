#include "facecap/model/eye_look.hpp"

#include <gtest/gtest.h>

#include <map>

#include "test_support.hpp"

namespace facecap {

namespace {
std::map<std::string, double> named(const FaceModel& model, const std::vector<std::pair<int, double>>& weights) {
  std::map<std::string, double> out;
  for (const auto& [k, w] : weights) out[model.expression_names[k]] = w;
  return out;
}
}  // namespace

TEST(EyeLookShapes, WeighTheShapesOfTheGazesDirectionByItsAngle) {
  FACECAP_REQUIRE_MODEL(model);
  const EyeLookShapes shapes(*model);
  EXPECT_EQ(shapes.indices().size(), 8u);
  // 15 degrees toward the subject's left and 6 up: the left eye looks out, the right one in.
  std::map<std::string, double> w = named(*model, shapes.weights(Vec2d(15.0, 6.0)));
  ASSERT_EQ(w.size(), 8u);
  EXPECT_NEAR(w["eyeLookOut_L"], 15.0 / kEyeLookFullDeg, 1e-12);
  EXPECT_NEAR(w["eyeLookIn_R"], 15.0 / kEyeLookFullDeg, 1e-12);
  EXPECT_NEAR(w["eyeLookUp_L"], 6.0 / kEyeLookFullDeg, 1e-12);
  EXPECT_NEAR(w["eyeLookUp_R"], 6.0 / kEyeLookFullDeg, 1e-12);
  for (const char* name : {"eyeLookIn_L", "eyeLookOut_R", "eyeLookDown_L", "eyeLookDown_R"}) EXPECT_EQ(w[name], 0.0);
  // Past the full angle the weights stay at 1.
  w = named(*model, shapes.weights(Vec2d(-45.0, -40.0)));
  EXPECT_EQ(w["eyeLookIn_L"], 1.0);
  EXPECT_EQ(w["eyeLookOut_R"], 1.0);
  EXPECT_EQ(w["eyeLookDown_L"], 1.0);
  EXPECT_EQ(w["eyeLookOut_L"], 0.0);
  EXPECT_EQ(w["eyeLookUp_R"], 0.0);
}

}  // namespace facecap
