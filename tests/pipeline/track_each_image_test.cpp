#include "facecap/pipeline/track_each_image.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/io/image_file.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;
using test::read_lines;

namespace {

Landmarks landmarks_of(const nlohmann::json& points) {
  Landmarks lm;
  for (size_t k = 0; k < lm.size(); ++k) lm[k] = Vec2f(points.at(k).at(0), points.at(k).at(1));
  return lm;
}

}  // namespace

// A folder of portraits of different sizes and people, one without a face
// and one that is no image: each portrait is fitted as `track IMAGE` fits it
// alone (the same row, number for number, and the same identity), the
// others are rows of their own, and the LFPW portrait's fitted landmarks lie
// where its annotation puts them.
TEST(TrackEachImage, EachImageIsFittedAsItsOwnRunAndTabled) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(biden, "portrait_biden.jpg");
  FACECAP_REQUIRE_DATA(lfpw, "lfpw_image_0010.png");
  FACECAP_REQUIRE_DATA(lfpw_pts, "lfpw_image_0010.pts");
  TempDir dir;
  const fs::path folder = dir.path() / "portraits";
  fs::create_directories(folder);
  fs::copy_file(obama, folder / "b_obama.jpg");
  fs::copy_file(biden, folder / "a_biden.jpg");
  fs::copy_file(biden, folder / "a_biden.png");  // the same name but for the extension (a JPEG inside)
  fs::copy_file(lfpw, folder / "c,lfpw.png");    // a comma, which the table quotes
  write_image((folder / "d_grey.png").string(), cv::Mat(200, 300, CV_8UC3, cv::Scalar::all(128)));
  std::ofstream(folder / "e_broken.jpg") << "not a jpeg";
  std::ofstream(folder / "notes.txt") << "not an image either, and not listed";

  TrackOptions o;
  o.capture.quiet = true;
  o.action_units = true;
  const fs::path out = dir.path() / "out";
  const EachImageSummary s = run_track_each_image(*model, folder, out, o);
  EXPECT_EQ(s.images, 6);
  EXPECT_EQ(s.with_face, 4);
  EXPECT_EQ(s.unreadable, 1);
  EXPECT_NE(s.first_error.find("e_broken.jpg"), std::string::npos) << s.first_error;

  const std::vector<std::string> csv = read_lines(out / "images.csv");
  ASSERT_EQ(csv.size(), 7u);
  const std::vector<std::string> header = split_csv_line(csv[0]);
  // image, status ... landmark_error, weights, gaze, identity, action units
  ASSERT_EQ(header.size(), 1 + 12 + 53 + 9 + 50 + 2 * 19u);
  EXPECT_EQ(header[0], "image");
  EXPECT_EQ(header[1], "status");
  EXPECT_EQ(header[1 + 12 + 53 + 9 + 49], "id_49");
  EXPECT_EQ(header[1 + 12 + 53 + 9 + 50], "AU01_r");
  EXPECT_EQ(header.back(), "AU45_c");
  const std::vector<std::string> jsonl = read_lines(out / "images.jsonl");
  ASSERT_EQ(jsonl.size(), 6u);
  const std::vector<std::string> names = {"a_biden.jpg", "a_biden.png", "b_obama.jpg",
                                          "c,lfpw.png",  "d_grey.png",  "e_broken.jpg"};
  const std::vector<std::string> folders = {"a_biden_jpg", "a_biden_png", "b_obama", "c,lfpw", "d_grey", ""};
  const std::vector<std::string> statuses = {"redetected", "redetected", "redetected", "redetected", "lost", "error"};
  for (size_t i = 0; i < names.size(); ++i) {
    const nlohmann::json row = nlohmann::json::parse(jsonl[i]);
    EXPECT_EQ(row["image"], names[i]);
    EXPECT_EQ(row["status"], statuses[i]) << names[i];
    EXPECT_EQ(row.contains("identity_weights"), i < 4) << names[i];
    EXPECT_EQ(csv[i + 1].find(names[i] == "c,lfpw.png" ? "\"c,lfpw.png\"," : names[i] + ","), 0u) << csv[i + 1];
    EXPECT_EQ(split_csv_line(csv[i + 1]).size(), header.size() + (i == 3 ? 1 : 0));  // the quoted comma splits here
    if (folders[i].empty()) continue;
    EXPECT_EQ(row["folder"], folders[i]);
    EXPECT_TRUE(fs::exists(out / folders[i] / "frames.csv")) << folders[i];
  }
  EXPECT_FALSE(fs::exists(out / "e_broken"));

  // Obama's portrait fitted alone: the same fields and identity.
  const fs::path alone = dir.path() / "alone";
  const TrackSummary single = run_track(*model, (folder / "b_obama.jpg").string(), alone, o);
  const std::vector<std::string> single_row = split_csv_line(read_lines(alone / "frames.csv")[1]);
  const std::vector<std::string> table_row = split_csv_line(csv[3]);
  for (size_t k = 2; k + 1 < single_row.size(); ++k)  // without frame, time and shot
    EXPECT_EQ(table_row[k - 1], single_row[k]) << read_lines(alone / "frames.csv")[0].substr(0, 80) << " field " << k;
  const nlohmann::json obama_row = nlohmann::json::parse(jsonl[2]);
  for (int k = 0; k < 50; ++k)
    EXPECT_DOUBLE_EQ(obama_row["identity_weights"][k].get<double>(), single.capture.identity.identity[k]) << k;
  EXPECT_EQ(obama_row["size"], nlohmann::json::parse("[910, 1137]"));
  // ...and the same action units, last in the table's row.
  const std::vector<std::string> single_units = split_csv_line(read_lines(alone / "action_units.csv")[1]);
  ASSERT_EQ(single_units.size(), 3 + 2 * 19u);
  for (size_t k = 3; k < single_units.size(); ++k)
    EXPECT_EQ(table_row[table_row.size() - single_units.size() + k], single_units[k]) << header[header.size() - 41 + k];

  // The LFPW portrait's fit against its annotation (0.033 of the eye
  // distance measured; dlib's own landmarks 0.029).
  const nlohmann::json lfpw_row = nlohmann::json::parse(jsonl[3]);
  const Landmarks truth = read_pts(lfpw_pts);
  EXPECT_LT(landmark_nme(landmarks_of(lfpw_row["fitted_landmarks"]), truth), 0.045);
}

// An input that is no folder is refused before anything is written.
TEST(TrackEachImage, AnInputThatIsNoFolderWritesNothing) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  EXPECT_THROW(run_track_each_image(*model, obama, dir.path() / "out", o), Error);
  EXPECT_THROW(run_track_each_image(*model, dir.path() / "missing", dir.path() / "out", o), Error);
  fs::create_directories(dir.path() / "empty");
  EXPECT_THROW(run_track_each_image(*model, dir.path() / "empty", dir.path() / "out", o), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

}  // namespace facecap
