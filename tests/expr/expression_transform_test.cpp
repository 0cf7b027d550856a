#include "facecap/expr/expression_transform.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/model/eye_look.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

int index_of(const FaceModel& model, const std::string& name) {
  const auto& n = model.expression_names;
  return static_cast<int>(std::find(n.begin(), n.end(), name) - n.begin());
}

// A talking neutral face: the jaw and lips move, everything else jitters a little.
std::vector<Eigen::VectorXf> speech(const FaceModel& model, int frames) {
  std::mt19937 rng(3);
  std::normal_distribution<float> jitter(0.0f, 0.02f);
  const int n = static_cast<int>(model.expression_names.size());
  const int jaw = index_of(model, "jawOpen");
  std::vector<Eigen::VectorXf> out;
  for (int t = 0; t < frames; ++t) {
    Eigen::VectorXf w(n);
    for (int k = 0; k < n; ++k) w[k] = std::clamp(0.05f + jitter(rng), 0.0f, 1.0f);
    w[jaw] = 0.15f + 0.12f * std::sin(0.7f * t);
    out.push_back(w);
  }
  return out;
}

double mean_step(const std::vector<TransformedFrame>& f, Eigen::VectorXf TransformedFrame::*member) {
  double s = 0;
  for (size_t i = 1; i < f.size(); ++i) s += ((f[i].*member) - (f[i - 1].*member)).cwiseAbs().mean();
  return s / (f.size() - 1);
}

}  // namespace

TEST(ExpressionMapper, MissingModelsAreAClearError) {
  TempDir dir;
  try {
    const ExpressionMapper mapper(dir.path() / "nowhere");
    mapper.pair(Emotion::kHappiness);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere"), std::string::npos) << e.what();
  }
}

TEST(ExpressionMapper, LinearBaselineShiftsByTheDomainMeans) {
  const ExpressionMapper mapper;
  const EmotionPair& p = mapper.pair(Emotion::kSadness);
  const Eigen::VectorXf w = Eigen::VectorXf::Constant(p.mean_neutral.size(), 0.1f);
  const MappedWeights m = mapper.map(w, Emotion::kNeutral, Emotion::kSadness, MappingMethod::kLinear);
  const Eigen::VectorXf expected = (w - p.mean_neutral + p.mean_emotion).cwiseMax(0.0f).cwiseMin(1.0f);
  EXPECT_LT((m.weights - expected).cwiseAbs().maxCoeff(), 1e-6f);
}

// A smile over synthetic speech, with one frame lost: one frame of delay
// (k = 1), the smile up, the key lip vertices kept near the speaker's, the
// window calmer than the mapping. The lip weight trades the two: the paper's
// alpha (10 per cm^2) keeps the lips within a third of a millimetre and lets
// more of the smile through than 1000 per cm^2, which pins them.
TEST(ExpressionTransform, SmilesKeepsLipsAndSmoothsWithADelayOfK) {
  FACECAP_REQUIRE_MODEL(model);
  const ExpressionMapper mapper;
  const Eigen::MatrixXd rows = lip_basis(*model);
  const int smile_l = index_of(*model, "mouthSmile_L"), smile_r = index_of(*model, "mouthSmile_R");
  const auto input = speech(*model, 40);
  struct Result {
    double rise = 0, lips_mm = 0;
  };
  const auto transform = [&](double lip_weight) {
    TransformOptions o;
    o.schedule = ExpressionSchedule::constant(Emotion::kHappiness, 1.0);
    o.lips.alpha = lip_weight;
    ExpressionTransformer transformer(mapper, rows, o);
    std::vector<TransformedFrame> out;
    for (int t = 0; t < 40; ++t) {
      const auto ready = transformer.push(t, t / 30.0, t == 20 ? std::nullopt : std::optional(input[t]));
      EXPECT_EQ(ready.size(), t == 0 ? 0u : 1u) << "frame " << t;  // k = 1 frame of delay
      out.insert(out.end(), ready.begin(), ready.end());
    }
    const auto rest = transformer.finish();
    EXPECT_EQ(rest.size(), 1u);
    out.insert(out.end(), rest.begin(), rest.end());
    EXPECT_EQ(out.size(), 40u);
    for (int t = 0; t < int(out.size()); ++t) EXPECT_EQ(out[t].index, t);
    EXPECT_FALSE(out.at(20).valid);  // a lost frame passes through
    Result r;
    std::vector<TransformedFrame> valid;
    for (const auto& f : out) {
      if (!f.valid) continue;
      valid.push_back(f);
      r.rise += 0.5 * (f.weights[smile_l] + f.weights[smile_r] - f.tracked[smile_l] - f.tracked[smile_r]);
      const Eigen::VectorXd d = rows * (f.weights - f.tracked).cast<double>();
      for (int v = 0; v < 4; ++v) r.lips_mm += 10.0 * d.segment<3>(3 * v).norm() / 4;
      EXPECT_GE(f.weights.minCoeff(), 0.0f);
      EXPECT_LE(f.weights.maxCoeff(), 1.0f);
    }
    r.rise /= valid.size();
    r.lips_mm /= valid.size();
    // The window mean is calmer than the per-frame mapping it averages.
    EXPECT_LT(mean_step(valid, &TransformedFrame::smoothed), mean_step(valid, &TransformedFrame::mapped));
    return r;
  };
  const Result paper = transform(LipCorrectionOptions{}.alpha), pinned = transform(1000.0);
  EXPECT_GT(paper.rise, 0.3);
  EXPECT_LT(paper.lips_mm, 0.5);  // the bar is 1 mm
  EXPECT_GT(paper.rise, pinned.rise + 0.02);
  EXPECT_LT(pinned.lips_mm, 0.2);
  std::printf("smile rise %.3f, lips %.3f mm (pinned: %.3f, %.4f mm)\n", paper.rise, paper.lips_mm, pinned.rise,
              pinned.lips_mm);
}

TEST(ExpressionTransform, IntensityZeroKeepsTheSource) {
  FACECAP_REQUIRE_MODEL(model);
  const ExpressionMapper mapper;
  TransformOptions o;
  o.schedule = ExpressionSchedule::constant(Emotion::kAnger, 0.0);
  ExpressionTransformer transformer(mapper, lip_basis(*model), o);
  const auto input = speech(*model, 5);
  for (int t = 0; t < 5; ++t) {
    for (const auto& f : transformer.push(t, t / 30.0, input[t])) {
      EXPECT_LT((f.mapped - f.tracked).cwiseAbs().maxCoeff(), 1e-6f);
    }
  }
}

TEST(ExpressionTransform, EveryShippedEmotionRaisesItsDefiningShapes) {
  FACECAP_REQUIRE_MODEL(model);
  const ExpressionMapper mapper;
  const auto input = speech(*model, 10);
  for (Emotion e : all_emotions()) {
    double rise = 0;
    const auto shapes = defining_shapes(e);
    for (const auto& w : input) {
      const MappedWeights m = mapper.map(w, Emotion::kNeutral, e);
      for (const auto& s : shapes) rise += (m.weights[index_of(*model, s)] - w[index_of(*model, s)]) / shapes.size();
    }
    EXPECT_GT(rise / input.size(), 0.3) << to_string(e);
  }
}

// The gaze's shapes (TransformOptions::kept_shapes, as the transform job
// sets them) come out as tracked, frame by frame, though the mapping moves
// them; a FACS edit that sets one of them still sets it.
TEST(ExpressionTransform, KeptShapesStayAsTrackedThoughTheMappingMovesThem) {
  FACECAP_REQUIRE_MODEL(model);
  const ExpressionMapper mapper;
  const std::vector<int> gaze = EyeLookShapes(*model).indices();
  ASSERT_EQ(gaze.size(), 8u);
  std::vector<Eigen::VectorXf> input = speech(*model, 30);
  for (int t = 0; t < 30; ++t)  // the eyes look about, down and to the side
    for (size_t k = 0; k < gaze.size(); ++k) input[t][gaze[k]] = 0.15f + 0.1f * std::sin(0.4f * t + float(k));
  auto run = [&](const TransformOptions& o) {
    ExpressionTransformer transformer(mapper, lip_basis(*model), o);
    std::vector<TransformedFrame> out;
    for (int t = 0; t < 30; ++t) {
      const auto ready = transformer.push(t, t / 30.0, input[t]);
      out.insert(out.end(), ready.begin(), ready.end());
    }
    const auto rest = transformer.finish();
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
  };
  TransformOptions o;
  o.schedule = ExpressionSchedule::constant(Emotion::kSurprise, 1.0);
  double moved = 0;
  for (const TransformedFrame& f : run(o))
    for (const int k : gaze) moved = std::max(moved, double(std::abs(f.weights[k] - f.tracked[k])));
  EXPECT_GT(moved, 0.03) << "the mapping alone leaves the gaze: nothing to keep";
  o.kept_shapes = gaze;
  const std::vector<TransformedFrame> kept = run(o);
  ASSERT_EQ(kept.size(), 30u);
  const int wide = index_of(*model, "eyeWide_L");
  for (const TransformedFrame& f : kept) {
    for (const int k : gaze) EXPECT_NEAR(f.weights[k], f.tracked[k], 1e-3f) << model->expression_names[k];
    EXPECT_GT(f.weights[wide], f.tracked[wide] + 0.2f) << "frame " << f.index;  // the rest is still surprise
  }
  // A FACS edit setting a kept shape sets it.
  o.shape_targets = {{gaze[4], 0.7f}};
  for (const TransformedFrame& f : run(o)) {
    EXPECT_NEAR(f.weights[gaze[4]], 0.7f, 1e-3f) << "frame " << f.index;
    EXPECT_NEAR(f.weights[gaze[5]], f.tracked[gaze[5]], 1e-3f) << "frame " << f.index;
  }
}

}  // namespace facecap
