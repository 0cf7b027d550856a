// Whether the face changed colour since the last frame: the gate that
// spares the moving covers' optical flow where nothing came across the face.
#include "facecap/swap/colour_change.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// A face of grainy skin (albedo 0.45-0.55) on a 128-texel grid at 1 mm a
// texel, every texel seen squarely.
FaceTexture skin(int seed = 1) {
  FaceTexture t;
  t.albedo.create(128, 128, CV_32FC3);
  cv::RNG(seed).fill(t.albedo, cv::RNG::UNIFORM, cv::Scalar::all(0.45), cv::Scalar::all(0.55));
  t.weight = cv::Mat(128, 128, CV_32F, cv::Scalar(1));
  return t;
}

// `t` with a disc of `diameter` texels at (64, 64) scaled by `factor`.
FaceTexture with_patch(FaceTexture t, int diameter, float factor) {
  cv::Mat disc(t.albedo.size(), CV_8U, cv::Scalar(0));
  cv::circle(disc, {64, 64}, diameter / 2, cv::Scalar(255), cv::FILLED);
  cv::Mat scaled = t.albedo * factor;
  scaled.copyTo(t.albedo, disc);
  return t;
}

}  // namespace

TEST(ColourChange, APatchOfNewColourOpensTheGateAndTheTrackingsSlipsDoNot) {
  ColourChange gate(1.0);
  const FaceTexture face = skin();
  EXPECT_TRUE(gate.changed(face, 0));  // no last frame: unknown
  EXPECT_FALSE(gate.changed(face, 1));
  // Each texel's grain a little different (+-10 %, under the 22 % of 0.2 in log).
  EXPECT_FALSE(gate.changed(skin(2), 2));
  // A patch 10 mm across 40 % darker (a hand's shadow, its edge): open.
  EXPECT_TRUE(gate.changed(with_patch(skin(2), 10, 0.6f), 3));
  // Back again: open too (the patch left), then closed.
  EXPECT_TRUE(gate.changed(skin(2), 4));
  EXPECT_FALSE(gate.changed(skin(2), 5));
  // Narrower than 4 mm (a feature's edge as the tracking slips): closed.
  EXPECT_FALSE(gate.changed(with_patch(skin(2), 3, 0.6f), 6));
  // 10 mm across but only 15 % darker: closed.
  EXPECT_FALSE(gate.changed(with_patch(skin(2), 10, 0.85f), 7));
}

TEST(ColourChange, WhatEitherFrameSawObliquelyDoesNotCount) {
  ColourChange gate(1.0);
  FaceTexture face = skin();
  face.weight.setTo(0.2f);  // seen at a glancing angle only
  EXPECT_TRUE(gate.changed(face, 0));
  EXPECT_FALSE(gate.changed(with_patch(face, 20, 0.5f), 1));
  face.weight.setTo(1.0f);
  EXPECT_FALSE(gate.changed(face, 2));  // the last frame saw it obliquely
  EXPECT_TRUE(gate.changed(with_patch(face, 20, 0.5f), 3));
}

TEST(ColourChange, AGapInTheFramesOrAResetIsUnknown) {
  ColourChange gate(1.0);
  const FaceTexture face = skin();
  EXPECT_TRUE(gate.changed(face, 0));
  EXPECT_FALSE(gate.changed(face, 1));
  EXPECT_TRUE(gate.changed(face, 3));  // frame 2 missing
  EXPECT_FALSE(gate.changed(face, 4));
  gate.reset();
  EXPECT_TRUE(gate.changed(face, 5));
  EXPECT_FALSE(gate.changed(face, -1));  // unknown numbers follow
  EXPECT_THROW(ColourChange(0.0), Error);
  ColourChangeOptions o;
  o.min_log_change = 0;
  EXPECT_THROW(ColourChange(1.0, o), Error);
}

}  // namespace facecap
