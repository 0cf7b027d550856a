#include "facecap/expr/training_data.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {

namespace {

const std::vector<std::string> kNames = {"mouthSmile_L",  "mouthSmile_R",  "cheekSquint_L", "cheekSquint_R",
                                         "browInnerUp_L", "browInnerUp_R", "jawOpen"};

std::vector<Eigen::VectorXf> speech() {
  std::vector<Eigen::VectorXf> s;
  for (int i = 0; i < 10; ++i) {
    Eigen::VectorXf w = Eigen::VectorXf::Zero(kNames.size());
    w[6] = 0.05f * i;  // jaw moves with speech
    s.push_back(w);
  }
  return s;
}

std::string error_of(const std::filesystem::path& p) {
  try {
    read_dataset_csv(p, kNames);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TrainingData, EmotionSamplesCarryTheProtoypeOverSpeech) {
  const auto rows = make_emotion_samples(Emotion::kHappiness, speech(), kNames, 200, 42);
  ASSERT_EQ(rows.size(), 200u);
  double smile = 0;
  for (const LabeledWeights& r : rows) {
    EXPECT_EQ(r.label, Emotion::kHappiness);
    EXPECT_GE(r.weights.minCoeff(), 0.0f);
    EXPECT_LE(r.weights.maxCoeff(), 1.0f);
    EXPECT_GE(r.weights[0], 0.35f * 0.85f - 1e-6f);  // intensity >= 0.35, asymmetry <= 15%
    smile += 0.5 * (r.weights[0] + r.weights[1]);
  }
  EXPECT_GT(smile / rows.size(), 0.5);
  // Reproducible from the seed.
  const auto again = make_emotion_samples(Emotion::kHappiness, speech(), kNames, 200, 42);
  EXPECT_EQ(again[17].weights, rows[17].weights);
}

TEST(TrainingData, CsvRoundTrip) {
  TempDir dir;
  auto rows = make_emotion_samples(Emotion::kSadness, speech(), kNames, 5, 1);
  rows.push_back({Emotion::kNeutral, speech()[3]});
  write_dataset_csv(dir.path() / "d.csv", rows, kNames);
  const auto back = read_dataset_csv(dir.path() / "d.csv", kNames);
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].label, rows[i].label);
    EXPECT_LT((back[i].weights - rows[i].weights).cwiseAbs().maxCoeff(), 1e-5f);
  }
}

TEST(TrainingData, MalformedCsvNamesTheProblem) {
  TempDir dir;
  write_dataset_csv(dir.path() / "good.csv", {{Emotion::kNeutral, speech()[1]}}, kNames);
  std::ifstream in(dir.path() / "good.csv");
  std::string header;
  std::getline(in, header);
  std::ofstream(dir.path() / "label.csv") << header << "\ncontempt,0,0,0,0,0,0,0\n";
  std::ofstream(dir.path() / "number.csv") << header << "\nneutral,0,zero,0,0,0,0,0\n";
  std::ofstream(dir.path() / "short.csv") << header << "\nneutral,0,0\n";
  std::ofstream(dir.path() / "column.csv") << "label,mouthSmile_L\nneutral,0\n";
  EXPECT_NE(error_of(dir.path() / "label.csv").find("contempt"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "number.csv").find("line 2"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "short.csv").find("line 2"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "column.csv").find("mouthSmile_R"), std::string::npos);
  EXPECT_NE(error_of(dir.path() / "missing.csv").find("not found"), std::string::npos);
}

}  // namespace facecap
