// facecap-train end to end: a short CycleGAN run on a generated training set
// gives networks the runtime loads and that move speech toward the emotion.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
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

TEST(Trainer, BadDatasetRequestsAreOneLineErrors) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  std::vector<LabeledWeights> rows;
  for (const auto& w : speech(*model, 5)) rows.push_back({Emotion::kNeutral, w});
  write_dataset_csv(dir.path() / "not_frames.csv", rows, model->expression_names);
  {  // A frames.csv as `facecap track` writes it (the columns the trainer reads).
    std::ofstream f(dir.path() / "frames.csv");
    f << "frame,time,status";
    for (const auto& n : model->expression_names) f << ',' << n;
    f << '\n';
    for (int i = 0; i < 5; ++i) {
      f << i << ',' << i / 30.0 << ",tracked";
      for (size_t k = 0; k < model->expression_names.size(); ++k) f << ",0.1";
      f << '\n';
    }
  }
  const std::string frames = (dir.path() / "frames.csv").string();
  const std::string out = (dir.path() / "set.csv").string();
  for (const std::string& args :
       {"expr-dataset --neutral " + (dir.path() / "missing.csv").string() + " -o " + out,
        "expr-dataset --neutral " + (dir.path() / "not_frames.csv").string() + " -o " + out,  // no status column
        "expr-dataset --neutral " + frames + " --real smiles -o " + out,
        "expr-dataset --neutral " + frames + " --real contempt=" + frames + "@0-1 -o " + out,
        "expr-dataset --neutral " + frames + " --real happiness=" + frames + "@5-1 -o " + out,
        "expr-dataset --neutral " + frames + " --real happiness=" + frames + "@30-40 -o " + out}) {  // no frames
    std::string text;
    EXPECT_NE(run_trainer(args, text), 0) << args;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << args << ": " << text;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  std::string text;
  EXPECT_EQ(
      run_trainer("expr-dataset --neutral " + frames + " --per-emotion 30 --real sadness=" + frames + "@0-1 -o " + out,
                  text),
      0)
      << text;
  EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace facecap
