// HarmonisedTexture: the photo's texture takes on the target's skin tone
// (eq. 6.3, on brightness and hue), and restart() forgets the target frames
// seen so far as if they had never come.
#include "facecap/swap/harmonised_texture.hpp"

#include <gtest/gtest.h>

#include <random>

#include "facecap/swap/face_swapper.hpp"
#include "facecap/swap/skin_texture.hpp"
#include "facecap/synth/synth_renderer.hpp"
#include "swap/two_faces.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

// A photo of a synthetic face and its true reconstruction.
struct Photo {
  cv::Mat image;
  SourceFace face;
};

Photo synthetic_photo(const FaceModel& model) {
  SynthOptions o;
  o.frames = 1;
  o.seed = 3;
  o.noise_sigma = 0.0;
  const SynthPerformance p = make_performance(model, o);
  std::mt19937_64 rng(1);
  return {SynthRenderer(model, p).render(p.frames[0], rng), test::source_face(model, p, 0)};
}

// `image` with its channels scaled by `gain` (B, G, R).
cv::Mat tinted(const cv::Mat& image, const cv::Scalar& gain) {
  cv::Mat f, out;
  image.convertTo(f, CV_32FC3);
  cv::multiply(f, gain, f);
  f.convertTo(out, CV_8UC3);
  return out;
}

// The mean colour (B, G, R) of the texture where it is wholly face (alpha 1).
cv::Vec3d mean_inside(const cv::Mat& texture) {
  std::vector<cv::Mat> ch;
  cv::split(texture, ch);
  const cv::Mat inside = ch[3] >= 0.999f;
  const cv::Scalar m = cv::mean(texture, inside);
  return {m[0], m[1], m[2]};
}

}  // namespace

TEST(HarmonisedTexture, TakesOnTheTargetsSkinTone) {
  FACECAP_REQUIRE_MODEL(model);
  const Photo photo = synthetic_photo(*model);
  const TriangleMesh skin = skin_mesh(*model);
  const SwapOptions options;
  const auto harmonised_with = [&](const cv::Mat& target) {
    HarmonisedTexture h(*model, photo.image, photo.face, skin, options);
    EXPECT_TRUE(h.texture().empty());
    h.add_target_frame(target, photo.face.camera_points, photo.face.camera, photo.face.lighting, {});
    EXPECT_EQ(h.target_frames(), 1);
    EXPECT_EQ(h.target_vertex_albedo().cols(), skin.num_vertices);
    return mean_inside(h.texture());
  };
  // The target is the photo itself, then the photo under a warmer, darker
  // grade: the texture's colour follows the grade (measured within 0.004 of
  // each channel's gain).
  const cv::Scalar gain(0.72, 0.9, 1.08);
  const cv::Vec3d same = harmonised_with(photo.image);
  const cv::Vec3d graded = harmonised_with(tinted(photo.image, gain));
  for (int c = 0; c < 3; ++c) {
    std::printf("channel %d: %.4f -> %.4f (ratio %.3f, grade %.2f)\n", c, same[c], graded[c], graded[c] / same[c],
                gain[c]);
    EXPECT_NEAR(graded[c] / same[c], gain[c], 0.01) << "channel " << c;
  }
}

TEST(HarmonisedTexture, RestartForgetsTheFramesSeenSoFar) {
  FACECAP_REQUIRE_MODEL(model);
  const Photo photo = synthetic_photo(*model);
  const TriangleMesh skin = skin_mesh(*model);
  const SwapOptions options;
  const cv::Mat graded = tinted(photo.image, cv::Scalar(0.8, 1.0, 1.1));
  const auto add = [&](HarmonisedTexture& h, const cv::Mat& frame) {
    h.add_target_frame(frame, photo.face.camera_points, photo.face.camera, photo.face.lighting, {});
  };
  HarmonisedTexture restarted(*model, photo.image, photo.face, skin, options);
  add(restarted, photo.image);
  add(restarted, photo.image);
  EXPECT_EQ(restarted.target_frames(), 2);
  restarted.restart();
  EXPECT_EQ(restarted.target_frames(), 0);
  add(restarted, graded);
  HarmonisedTexture fresh(*model, photo.image, photo.face, skin, options);
  add(fresh, graded);
  EXPECT_EQ(cv::norm(restarted.texture(), fresh.texture(), cv::NORM_INF), 0.0);
  // Without the restart the frames before would have counted.
  HarmonisedTexture kept(*model, photo.image, photo.face, skin, options);
  add(kept, photo.image);
  add(kept, graded);
  EXPECT_GT(cv::norm(kept.texture(), fresh.texture(), cv::NORM_INF), 0.01);
}

}  // namespace facecap
