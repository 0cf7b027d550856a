// The shading refinement on synthetic truth and on real footage. The issue's
// bars that are not met (see the note on issue 4) are not asserted here;
// these guard what the refinement does achieve.
#include "facecap/pipeline/refine_eval.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>

#include "facecap/core/error.hpp"
#include "facecap/render/shading.hpp"

#include "test_support.hpp"

namespace facecap {

// The two lighting measures against constructed errors: a face's visible
// normals (camera frame, facing the camera within about 70 deg) leave some
// coefficient directions nearly unseen.
TEST(RefineEval, ShadingErrorMeasuresWhatTheImageDetermines) {
  Positions normals(3, 0);
  std::vector<Vec3f> list;
  for (double a = -1.2; a <= 1.2001; a += 0.1) {
    for (double b = -1.2; b <= 1.2001; b += 0.1) {
      list.emplace_back(float(std::sin(a) * std::cos(b)), float(std::sin(b)), float(-std::cos(a) * std::cos(b)));
    }
  }
  normals.resize(3, Eigen::Index(list.size()));
  for (size_t i = 0; i < list.size(); ++i) normals.col(Eigen::Index(i)) = list[i];
  const std::vector<bool> visible(list.size(), true);
  ShCoeffs truth;
  truth << 0.75, 0.2, 0.1, 0.25, -0.05, 0.0, -0.02, 0.06, -0.01;  // like the renders' (seed 2)

  // Scale is free in both.
  EXPECT_NEAR(scaled_lighting_error(2.5 * truth, truth), 0.0, 1e-12);
  EXPECT_NEAR(scaled_shading_error(2.5 * truth, truth, normals, visible), 0.0, 1e-12);
  // The terms say where the error lies: an n_z term too strong shows there
  // most, and the scale's correction spreads a little of it over the rest.
  ShCoeffs strong_front = truth;
  strong_front[3] += 0.1;
  const ShCoeffs terms = scaled_lighting_error_terms(strong_front, truth);
  EXPECT_NEAR(terms.norm(), scaled_lighting_error(strong_front, truth), 1e-12);
  Eigen::Index largest = -1;
  terms.cwiseAbs().maxCoeff(&largest);
  EXPECT_EQ(largest, 3);
  EXPECT_NEAR(terms[3], 0.0835 / truth.norm(), 0.002);

  // The directions of coefficient space these normals see least and most
  // (singular vectors of the SH basis over them, viewer frame).
  Eigen::MatrixXd basis(list.size(), 9);
  for (size_t i = 0; i < list.size(); ++i) {
    const Vec3f v = to_viewer_frame(list[i]);
    basis.row(Eigen::Index(i)) = sh_basis<double>(v.x(), v.y(), v.z()).transpose();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(basis, Eigen::ComputeThinV);
  const ShCoeffs least = svd.matrixV().col(8), most = svd.matrixV().col(0);
  // The same coefficient error, 0.2 of the lighting, along each.
  const ShCoeffs unseen =
      truth + 0.2 * truth.norm() * (least - least.dot(truth) / truth.squaredNorm() * truth).normalized();
  const ShCoeffs seen =
      truth + 0.2 * truth.norm() * (most - most.dot(truth) / truth.squaredNorm() * truth).normalized();
  EXPECT_NEAR(scaled_lighting_error(unseen, truth), 0.2, 0.02);
  EXPECT_NEAR(scaled_lighting_error(seen, truth), 0.2, 0.02);
  // The image barely sees one and plainly sees the other: the smallest
  // singular value is 0.028 of the largest, and the shading errors are 0.043
  // and 0.79 of the shading's spread.
  const double e_unseen = scaled_shading_error(unseen, truth, normals, visible);
  const double e_seen = scaled_shading_error(seen, truth, normals, visible);
  EXPECT_LT(e_unseen, 0.1 * e_seen);
  EXPECT_GT(e_seen, 0.5);
  // Invisible normals count for nothing.
  std::vector<bool> none(list.size(), false);
  EXPECT_EQ(scaled_shading_error(seen, truth, normals, none), 0.0);
}

TEST(RefineEval, SyntheticAlbedoIsRecoveredAndNothingDiverges) {
  FACECAP_REQUIRE_MODEL(model);
  RefineEvalOptions o;
  o.frames = 8;
  o.seed = 2;  // the seed whose lighting the eye and mouth rims threw furthest off
  o.quiet = true;
  const RefineEvalResult r = evaluate_refine_synthetic(*model, o);
  EXPECT_EQ(r.frames, 8);
  EXPECT_GE(r.levels, 2);
  EXPECT_GE(r.albedo_corr, 0.95);
  EXPECT_TRUE(std::isfinite(r.lighting_error_rel));
  // Its terms add up to it: the norm of the terms' means is at most the
  // mean of the norms, and their sum at least it (|e|_2 <= |e|_1).
  EXPECT_LE(r.lighting_error_terms.norm(), r.lighting_error_rel + 1e-12);
  EXPECT_GE(r.lighting_error_terms.sum(), r.lighting_error_rel - 1e-12);
  EXPECT_GT(r.lighting_error_terms.minCoeff(), 0.0);
  // With the rims of the eye and mouth holes among the lighting's samples
  // (their colour is the eye white's, the teeth's) this was 0.39 (12 frames);
  // now 0.21. The bar is 0.10.
  EXPECT_LT(r.lighting_error_rel, 0.3);
  // Judged by the shading it gives the face: 0.38 of the shading's spread is
  // wrong (8 frames). The alternation keeps what the first frame's estimate,
  // made against a uniform albedo, says: with only that estimate made
  // against the true albedo this is 0.04-0.14 on seeds 1-4 (note on issue 4).
  EXPECT_LT(r.shading_error_rel, 0.5);
  // Refined depth stays within a fraction of a millimetre of the truth.
  EXPECT_LT(r.vertex_error_mm, 0.2);
  EXPECT_TRUE(std::isfinite(r.normal_error_deg));
  // False detail stays bounded: with the observations at the silhouette and
  // the eye and mouth rims kept, this was 2.4 times the coarse error; with
  // every visible vertex in the displacement solve (not only those facing the
  // camera within 45 degrees) 2.6 times; now 1.5 (seed 1) and 1.3 (seed 2) times.
  EXPECT_LT(r.normal_error_deg, 1.7 * r.normal_error_coarse_deg);
  // The split by true detail adds up to the whole: the wrinkles cover about a
  // tenth of the face's pixels, and flat skin is where the false detail is.
  EXPECT_GT(r.detail_pixel_fraction, 0.05);
  EXPECT_LT(r.detail_pixel_fraction, 0.2);
  const double f = r.detail_pixel_fraction;
  EXPECT_NEAR(f * r.normal_error_detail_deg + (1 - f) * r.normal_error_flat_deg, r.normal_error_deg, 1e-6);
  EXPECT_NEAR(f * r.normal_error_detail_coarse_deg + (1 - f) * r.normal_error_flat_coarse_deg,
              r.normal_error_coarse_deg, 1e-6);
  EXPECT_GT(r.normal_error_detail_coarse_deg, 3.0);
  EXPECT_LT(r.normal_error_flat_coarse_deg, 0.1);
  // The finest level displaced by the truth's own wrinkles (the oracle) meets
  // the bar, half the coarse error: the hierarchy can hold the detail,
  // it is the solve that does not find it. Seeds 1 and 2, 30 frames: 0.22 of
  // 0.68 and 0.66 deg; 1.8 and 1.7 deg on the wrinkles' pixels against 5.9
  // and 5.7.
  EXPECT_LT(r.normal_error_oracle_deg, 0.5 * r.normal_error_coarse_deg);
  EXPECT_LT(r.normal_error_detail_oracle_deg, 0.4 * r.normal_error_detail_coarse_deg);
}

TEST(RefineEval, WithTheTrueShadingTheSolveRecoversSomeWrinkles) {
  FACECAP_REQUIRE_MODEL(model);
  RefineEvalOptions o;
  o.frames = 4;
  o.seed = 1;
  o.quiet = true;
  o.true_shading = true;
  const RefineEvalResult known = evaluate_refine_synthetic(*model, o);
  o.true_shading = false;
  const RefineEvalResult estimated = evaluate_refine_synthetic(*model, o);
  // Seed 1, 4 frames: on the wrinkles' pixels 5.67 deg with the true
  // lighting and albedo, 5.93 with the estimated ones, 5.92 for the coarse
  // mesh; on flat skin 0.34 and 0.38 (coarse 0.03). The solve itself moves toward the truth; the estimates' errors
  // (their product is right on the coarse mesh, their split is not) undo it.
  EXPECT_LT(known.normal_error_detail_deg, known.normal_error_detail_coarse_deg - 0.1);
  EXPECT_LT(known.normal_error_detail_deg, estimated.normal_error_detail_deg - 0.1);
  EXPECT_LT(known.normal_error_flat_deg, estimated.normal_error_flat_deg);
}

TEST(RefineEval, KnownShadingOfTheWrongMeshIsAnError) {
  FACECAP_REQUIRE_MODEL(model);
  Refiner refiner = make_face_refiner(*model, RefineOptions{});
  KnownShading known;
  known.lighting.setZero();
  known.albedo = Positions::Constant(3, 10, 0.5f);
  const cv::Mat image(720, 1280, CV_8UC3, cv::Scalar::all(128));
  const Positions coarse = model->evaluate(Eigen::VectorXf::Zero(model->num_identity()),
                                           Eigen::VectorXf::Zero(model->num_expressions()), regions::kFace);
  EXPECT_THROW(refiner.refine(image, coarse, PinholeCamera::centered(1000, 1280, 720), &known), Error);
  EXPECT_FALSE(refiner.initialised());
}

TEST(RefineEval, RealFootageRefinedMeshExplainsTheImageBetter) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  CaptureOptions c;
  c.quiet = true;
  c.max_frames = 40;
  const RefineVideoResult r = evaluate_refine_video(*model, video.string(), c, RefineOptions{});
  EXPECT_EQ(r.frames, 40);
  EXPECT_TRUE(std::isfinite(r.photometric_refined));
  EXPECT_LT(r.photometric_refined, r.photometric_coarse);
  // The bar for the refined error (4.6 here); the recovered albedo
  // and lighting explain the skin (coarse 4.8). When the depth test rejected
  // tilted skin, its albedo was never estimated: coarse 7.2, refined 7.0.
  EXPECT_LT(r.photometric_refined, 6.0);
  EXPECT_LT(r.photometric_coarse, 6.0);
  // The floor: each vertex's shading matched to its own colour, within what a
  // normal facing the camera can receive, each vertex on its own: what the
  // best displacement field could reach (3.8 on 60 frames, 22 % below the
  // coarse error). A wrong frame for the normals or the colours puts it above
  // the refinement.
  EXPECT_TRUE(std::isfinite(r.photometric_shading_floor));
  EXPECT_LT(r.photometric_shading_floor, r.photometric_refined);
  EXPECT_LT(r.photometric_shading_floor, 0.85 * r.photometric_coarse);
}

}  // namespace facecap
