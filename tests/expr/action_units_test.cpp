// FACS action units read off the ICT weights (action_units.hpp): OpenFace's
// columns, the 0-5 scale, and each unit's shapes moving the face the way
// FACS describes that unit.
#include "facecap/expr/action_units.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "facecap/core/error.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

// Every shape the table names, and one it does not.
std::vector<std::string> table_shapes() {
  std::vector<std::string> names = {"tongueOut"};
  for (const ActionUnit& unit : action_units())
    for (const std::string& shape : unit.shapes) names.push_back(shape);
  return names;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

}  // namespace

TEST(ActionUnits, AreOpenFacesColumnsInFacsOrder) {
  const auto& units = action_units();
  EXPECT_EQ(units.front().column('r'), "AU01_r");
  EXPECT_EQ(units.back().column('c'), "AU45_c");
  for (size_t u = 1; u < units.size(); ++u) EXPECT_LT(units[u - 1].number, units[u].number);
  // OpenFace's intensity units that ICT has a shape for are all here...
  for (int number : {1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 20, 26, 45})
    EXPECT_GE(action_unit_index(number), 0) << number;
  // ...and the two it has none for are left out, not guessed.
  EXPECT_EQ(action_unit_index(23), -1);
  EXPECT_EQ(action_unit_index(25), -1);
}

TEST(ActionUnits, IntensityIsTheShapesMeanWeightOnFacsScale) {
  const std::vector<std::string> names = table_shapes();
  const ActionUnitReader reader(names);
  ASSERT_EQ(reader.size(), static_cast<int>(action_units().size()));
  Eigen::VectorXf w = Eigen::VectorXf::Zero(static_cast<Eigen::Index>(names.size()));
  w[index_of(names, "mouthSmile_L")] = 0.6f;
  w[index_of(names, "mouthSmile_R")] = 0.2f;
  w[index_of(names, "jawOpen")] = 1.0f;
  w[index_of(names, "eyeBlink_L")] = 1.0f;  // a wink: half the unit
  w[index_of(names, "tongueOut")] = 1.0f;   // no unit of its own
  const Eigen::VectorXd a = reader.intensities(w);
  EXPECT_NEAR(a[action_unit_index(12)], 2.0, 1e-6);
  EXPECT_NEAR(a[action_unit_index(26)], 5.0, 1e-6);
  EXPECT_NEAR(a[action_unit_index(45)], 2.5, 1e-6);
  EXPECT_NEAR(a.sum(), 2.0 + 5.0 + 2.5, 1e-6);  // nothing else moved
}

TEST(ActionUnits, AModelWithoutAUnitsShapeIsAnErrorNamingIt) {
  std::vector<std::string> names = table_shapes();
  names.erase(names.begin() + index_of(names, "mouthDimple_R"));
  try {
    ActionUnitReader reader(names);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mouthDimple_R"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("AU14"), std::string::npos) << e.what();
  }
}

TEST(ActionUnits, AnEditIsReadFromUnitsAndIntensities) {
  const std::vector<ActionUnitTarget> targets = parse_action_unit_targets("AU12=3, au4=0,6=2.5");
  ASSERT_EQ(targets.size(), 3u);
  EXPECT_EQ(targets[0].number, 12);
  EXPECT_DOUBLE_EQ(targets[0].intensity, 3.0);
  EXPECT_EQ(targets[1].number, 4);
  EXPECT_EQ(targets[2].number, 6);
  EXPECT_DOUBLE_EQ(targets[2].intensity, 2.5);
  EXPECT_EQ(describe(targets), "AU12=3, AU4=0, AU6=2.5");
  // Each unit's shapes at its intensity over 5.
  const std::vector<std::string> names = table_shapes();
  const auto weights = ActionUnitReader(names).shape_weights(targets);
  ASSERT_EQ(weights.size(), 6u);  // two halves each
  EXPECT_EQ(names[weights[0].first], "mouthSmile_L");
  EXPECT_EQ(names[weights[1].first], "mouthSmile_R");
  EXPECT_FLOAT_EQ(weights[1].second, 0.6f);
  EXPECT_EQ(names[weights[2].first], "browDown_L");
  EXPECT_FLOAT_EQ(weights[2].second, 0.0f);
  EXPECT_FLOAT_EQ(weights[5].second, 0.5f);
}

TEST(ActionUnits, ABadEditSaysWhatIsWrong) {
  auto message = [](const std::string& text) {
    try {
      parse_action_unit_targets(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("AU25=2").find("no shape for AU25"), std::string::npos) << message("AU25=2");
  EXPECT_NE(message("AU12=7").find("between 0 and 5"), std::string::npos) << message("AU12=7");
  EXPECT_NE(message("AU12=nan").find("between 0 and 5"), std::string::npos) << message("AU12=nan");
  EXPECT_NE(message("AU12").find("AU<number>=<intensity 0-5>"), std::string::npos);
  EXPECT_NE(message("smile=3").find("not \"smile=3\""), std::string::npos) << message("smile=3");
  EXPECT_NE(message("AU12=1,AU12=2").find("given twice"), std::string::npos);
  EXPECT_NE(message("").find("no unit given"), std::string::npos);
}

// Each unit's shapes at full weight on the mean face, against the movement
// FACS describes for the unit (Ekman, Friesen and Hager's manual), measured
// at the model's landmark vertices (iBUG numbers; model space: x toward the
// face's left, y up). This checks the table against the model it reads.
TEST(ActionUnits, EachUnitMovesTheFaceAsFacsDescribesIt) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXf identity = Eigen::VectorXf::Zero(model->num_identity());
  const Eigen::VectorXf rest = Eigen::VectorXf::Zero(model->num_expressions());
  const Positions neutral = model->evaluate(identity, rest);
  std::map<int, Positions> moved;  // by unit number
  for (const ActionUnit& unit : action_units()) {
    Eigen::VectorXf w = rest;
    for (const std::string& shape : unit.shapes) w[model->expression_index(shape)] = 1.0f;
    moved.emplace(unit.number, model->evaluate(identity, w));
  }
  auto point = [&](const Positions& p, int landmark) -> Vec3d {
    return 10.0 * p.col(model->landmarks.vertices[landmark]).cast<double>();  // mm
  };
  // Mean upward (y) movement of some landmarks, mm.
  auto rise = [&](int unit, std::initializer_list<int> landmarks) {
    double sum = 0;
    for (int i : landmarks) sum += point(moved.at(unit), i).y() - point(neutral, i).y();
    return sum / double(landmarks.size());
  };
  // Mean movement away from the face's midline (x), mm.
  auto outward = [&](int unit, std::initializer_list<int> landmarks) {
    double sum = 0;
    for (int i : landmarks) {
      const double x0 = point(neutral, i).x();
      sum += (point(moved.at(unit), i).x() - x0) * (x0 > 0 ? 1.0 : -1.0);
    }
    return sum / double(landmarks.size());
  };
  const auto inner_brow = {21, 22}, outer_brow = {17, 26}, brows = {17, 18, 19, 20, 21, 22, 23, 24, 25, 26};
  const auto upper_lids = {37, 38, 43, 44}, lower_lids = {40, 41, 46, 47};
  const auto corners = {48, 54}, nose_wings = {31, 35};
  const auto upper_lip = {50, 51, 52}, lower_lip = {56, 57, 58};

  EXPECT_GT(rise(1, inner_brow), 2.0);  // AU1: the brows' inner ends up...
  EXPECT_GT(rise(1, inner_brow), 2 * rise(1, outer_brow));
  EXPECT_GT(rise(2, outer_brow), 2.0);  // AU2: ...their outer ends up
  EXPECT_GT(rise(2, outer_brow), 2 * rise(2, inner_brow));
  EXPECT_LT(rise(4, brows), -0.5);  // AU4: brows down and drawn together
  EXPECT_LT(outward(4, inner_brow), -0.5);
  EXPECT_GT(rise(5, upper_lids), 1.5);  // AU5: upper lids up
  EXPECT_GT(rise(6, lower_lids), 0.5);  // AU6: the cheeks lifted, pushing the lower lids up...
  EXPECT_GT(rise(6, corners), 0.3);     // ...and the mouth's corners a little with them
  EXPECT_GT(rise(7, lower_lids), 1.0);  // AU7: lower lids tightened up, upper lids not raised,
  EXPECT_LE(rise(7, upper_lids), 0.0);
  EXPECT_LT(std::abs(rise(7, corners)), 0.2);  // the cheeks left where they are
  EXPECT_GT(rise(9, nose_wings), 3.0);         // AU9: the nose's wings pulled up
  EXPECT_GT(rise(10, upper_lip), 2.0);         // AU10: upper lip up
  EXPECT_GT(rise(12, corners), 3.0);           // AU12: lip corners up and out
  EXPECT_GT(outward(12, corners), 2.0);
  EXPECT_GT(rise(14, corners), 1.0);  // AU14: corners tightened, moving less sideways than in a smile
  EXPECT_LT(outward(14, corners), outward(12, corners) / 2);
  EXPECT_LT(rise(15, corners), -2.0);     // AU15: lip corners down
  EXPECT_GT(rise(17, {8, 57}), 3.0);      // AU17: chin and lower lip pushed up
  EXPECT_LT(outward(18, corners), -2.0);  // AU18: corners drawn to the middle
  EXPECT_GT(outward(20, corners), 3.0);   // AU20: corners stretched sideways more than up or down
  EXPECT_GT(outward(20, corners), 2 * std::abs(rise(20, corners)));
  EXPECT_GT(rise(22, upper_lip), 3.0);  // AU22: the lips funnel open...
  EXPECT_LT(rise(22, lower_lip), -3.0);
  EXPECT_LT(outward(22, corners), -1.0);  // ...with the corners in
  EXPECT_GT(rise(24, lower_lip), 1.0);    // AU24: the lower lip pressed up against the upper
  EXPECT_LT(rise(26, {8}), -10.0);        // AU26: the jaw drops
  EXPECT_GT(rise(28, lower_lip), 3.0);    // AU28: both lips sucked in between the teeth
  EXPECT_LT(rise(28, upper_lip), -3.0);
  EXPECT_LT(rise(45, upper_lids), -5.0);  // AU45: lids closed
}

}  // namespace facecap
