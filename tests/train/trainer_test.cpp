// facecap-train end to end: a short CycleGAN run on a generated training set
// gives networks the runtime loads and that move speech toward the emotion.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <random>

#include "facecap/core/temp_dir.hpp"
#include "facecap/expr/expression_mapper.hpp"
#include "facecap/expr/training_data.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

int run_trainer(const std::string& args, std::string& out) {
  const std::string cmd = std::string(FACECAP_TRAIN_BINARY) + " " + args + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  while (pipe && std::fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int status = pipe ? ::pclose(pipe) : -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<Eigen::VectorXf> speech(const FaceModel& model, int frames) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 0.15f);
  std::vector<Eigen::VectorXf> out;
  for (int t = 0; t < frames; ++t) {
    Eigen::VectorXf w(model.num_expressions());
    for (int k = 0; k < w.size(); ++k) w[k] = u(rng);
    w[model.expression_index("jawOpen")] = 0.1f + 0.1f * std::sin(0.5f * t);
    out.push_back(w);
  }
  return out;
}

}  // namespace

TEST(Trainer, ShortRunGivesLoadableModelsThatSmile) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const auto talk = speech(*model, 200);
  std::vector<LabeledWeights> rows;
  for (const auto& w : talk) rows.push_back({Emotion::kNeutral, w});
  const auto happy = make_emotion_samples(Emotion::kHappiness, talk, model->expression_names, 400, 3);
  rows.insert(rows.end(), happy.begin(), happy.end());
  write_dataset_csv(dir.path() / "data.csv", rows, model->expression_names);

  std::string out;
  const std::string data = (dir.path() / "data.csv").string();
  ASSERT_EQ(run_trainer("expr " + data + " --to happiness --iterations 400 -o " +
                            (dir.path() / "models" / "neutral-happiness").string(),
                        out),
            0)
      << out;
  const ExpressionMapper mapper(dir.path() / "models");
  const int smile_l = model->expression_index("mouthSmile_L"), smile_r = model->expression_index("mouthSmile_R");
  double rise = 0;
  for (int t = 0; t < 50; ++t) {
    const MappedWeights m = mapper.map(talk[t], Emotion::kNeutral, Emotion::kHappiness);
    ASSERT_TRUE(m.weights.allFinite());
    EXPECT_GE(m.weights.minCoeff(), 0.0f);
    EXPECT_LE(m.weights.maxCoeff(), 1.0f);
    rise += 0.5 * (m.weights[smile_l] + m.weights[smile_r] - talk[t][smile_l] - talk[t][smile_r]) / 50;
  }
  EXPECT_GT(rise, 0.3);

  // A training set without the target emotion is refused with one line.
  out.clear();
  EXPECT_NE(run_trainer("expr " + data + " --to sadness -o " + (dir.path() / "sad").string(), out), 0);
  EXPECT_NE(out.find("no sadness rows"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "sad" / "G.fcnn"));
}

}  // namespace facecap
