// track --action-units (action_unit_table.hpp): OpenFace's AU columns, and
// the units on real footage whose expressions are known.
#include "facecap/pipeline/action_unit_table.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "facecap/core/csv_line.hpp"
#include "facecap/io/input.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

std::vector<std::string> table_shapes() {
  std::vector<std::string> names;
  for (const ActionUnit& unit : action_units())
    for (const std::string& shape : unit.shapes) names.push_back(shape);
  return names;
}

}  // namespace

TEST(ActionUnitTable, GivesIntensitiesThenPresenceUnderOpenFacesColumns) {
  const std::vector<std::string> names = table_shapes();
  const ActionUnitTable table(names);
  const std::vector<std::string> header = split_csv_line(table.header());
  const size_t units = action_units().size();
  ASSERT_EQ(header.size(), 3 + 2 * units);
  EXPECT_EQ(header[0], "frame");
  EXPECT_EQ(header[1], "time");
  EXPECT_EQ(header[2], "status");
  EXPECT_EQ(header[3], "AU01_r");
  EXPECT_EQ(header[3 + units], "AU01_c");
  EXPECT_EQ(header.back(), "AU45_c");

  Eigen::VectorXf w = Eigen::VectorXf::Zero(static_cast<Eigen::Index>(names.size()));
  w[0] = 0.19f;  // browInnerUp_L and _R: AU1 at 1.05, present
  w[1] = 0.23f;
  w[names.size() - 2] = 0.3f;  // eyeBlink_L and _R: AU45 at 1.5
  w[names.size() - 1] = 0.3f;
  const Eigen::VectorXd intensities = table.intensities(w);
  const std::vector<std::string> row = split_csv_line(table.row(12, 0.5, "tracked", &intensities));
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(row[0], "12");
  EXPECT_EQ(row[1], "0.5");
  EXPECT_EQ(row[2], "tracked");
  EXPECT_NEAR(std::stod(row[3]), 1.05, 1e-5);
  EXPECT_EQ(row[3 + units], "1");
  EXPECT_NEAR(std::stod(row[3 + units - 1]), 1.5, 1e-5);
  EXPECT_EQ(row[3 + units - 2], "0");  // AU28 not moved
  EXPECT_EQ(row.back(), "1");
  EXPECT_EQ(row[4], "0");  // AU2 not moved
  EXPECT_EQ(row[4 + units], "0");

  // The same for frames.jsonl, keyed by the unit.
  const nlohmann::json json = ActionUnitTable::intensities_json(intensities);
  EXPECT_EQ(json.size(), units);
  EXPECT_NEAR(double(json["AU01"]), 1.05, 1e-6);
  EXPECT_NEAR(double(json["AU45"]), 1.5, 1e-6);
  EXPECT_EQ(double(json["AU12"]), 0.0);

  // A frame without a face: its fields empty, never made-up numbers.
  EXPECT_EQ(table.row(13, 0.54, "lost", nullptr), "13,0.54,lost" + std::string(2 * units, ','));
}

// emotions_pexels_640x360.mp4 smiles broadly from 10 to 19.7 s and cries
// (brows drawn down, before the hands come up) in its first 2 s, the
// segments the expression models were trained on (README). Whole clip, as
// `track` fits it: smile / crying means of AU12 1.88 / 0.92, AU6 1.42 / 0.82,
// AU4 0.00 / 0.70; AU12 present in 78 % of the smile's frames.
TEST(ActionUnitTable, ASmileAndCryingShowTheirUnitsOnRealFootage) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "emotions_pexels_640x360.mp4");
  const ActionUnitReader reader(model->expression_names);
  std::map<std::string, Eigen::VectorXd> sum;
  std::map<std::string, int> frames, smile_present;
  auto row = [](int number) { return static_cast<Eigen::Index>(action_unit_index(number)); };
  CaptureOptions o;
  o.quiet = true;
  o.gaze = false;
  auto source = open_input(video.string());
  run_capture(*model, *source, o, [&](const CapturedFrame& f) {
    if (f.status == TrackStatus::kLost) return;
    const std::string segment = f.time < 2.0 ? "crying" : (f.time >= 10.0 && f.time < 19.7 ? "smile" : "");
    if (segment.empty()) return;
    const Eigen::VectorXd units = reader.intensities(f.fit.expression);
    if (!sum.contains(segment)) sum[segment] = Eigen::VectorXd::Zero(units.size());
    sum[segment] += units;
    ++frames[segment];
    smile_present[segment] += units[row(12)] >= kActionUnitPresentFrom;
  });
  ASSERT_GE(frames["crying"], 45);
  ASSERT_GE(frames["smile"], 220);
  const Eigen::VectorXd smile = sum["smile"] / frames["smile"], crying = sum["crying"] / frames["crying"];
  EXPECT_GT(smile[row(12)], crying[row(12)] + 0.5) << smile[row(12)] << " / " << crying[row(12)];
  EXPECT_GT(smile[row(6)], crying[row(6)] + 0.3) << smile[row(6)] << " / " << crying[row(6)];
  EXPECT_GT(crying[row(4)], smile[row(4)] + 0.35) << crying[row(4)] << " / " << smile[row(4)];
  EXPECT_GE(smile_present["smile"], 0.6 * frames["smile"]);
}

}  // namespace facecap
