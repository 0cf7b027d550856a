// WrinkleShading: the target's fine motion since its reference frame shades
// the swapped face where that motion is, and a fold the target already had
// in its reference frame (the photo's own, as far as the swap knows) is left
// to the texture.
#include "facecap/swap/wrinkle_shading.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "facecap/model/regions.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/swap/skin_texture.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

constexpr int kWidth = 640, kHeight = 480;

struct WrinkleCase {
  PinholeCamera camera = PinholeCamera::centered(900, kWidth, kHeight);
  Positions face;  // the mean face's region in camera space
  MeshHierarchy hierarchy;
  Positions flat;    // the finest level with no detail
  Positions folded;  // the same with a 1 mm bump on the left cheek
  Vec3f bump_centre;
  ShCoeffs lighting;
  // Expression weights: the source's (none), and a target frame's farther
  // from it (eq. 6.2's reference stays on the frame nearest the source's).
  Eigen::VectorXf neutral, moved;

  explicit WrinkleCase(const FaceModel& model) {
    HeadPose pose;
    pose.translation = Vec3d(0, 0, 50);
    face = to_camera(model.evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace), pose);
    hierarchy =
        MeshHierarchy::build(model.region_polygons(regions::kFace), regions::kFace.num_vertices(), face, camera);
    const int finest = hierarchy.num_levels() - 1;
    flat = hierarchy.prolong_from_coarse(face, finest);
    // Between the left eye's lower lid (iBUG 41) and the mouth's corner (48).
    const std::vector<int>& lm = model.landmarks.vertices;
    bump_centre = 0.5f * (face.col(lm[41]) + face.col(lm[48]));
    const Positions normals = level_normals(hierarchy.level(finest), flat);
    folded = flat;
    const float sigma = 0.4f;  // cm
    for (int v = 0; v < flat.cols(); ++v) {
      const float d2 = (flat.col(v) - bump_centre).squaredNorm();
      folded.col(v) += 0.1f * std::exp(-0.5f * d2 / (sigma * sigma)) * normals.col(v);
    }
    lighting << 0.7, 0.35, -0.2, 0.45, 0, 0, 0, 0, 0;
    neutral = Eigen::VectorXf::Zero(model.num_expressions());
    moved = neutral;
    moved[0] = 0.6f;
  }

  // `render` (grey) shaded by `w` for a target frame with fine mesh `fine`
  // and expression weights `expression`, the swapped face the target's own.
  cv::Mat shade(WrinkleShading& w, const Positions& fine, const Eigen::VectorXf& expression) const {
    cv::Mat render(kHeight, kWidth, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
    w.shade(hierarchy, fine, expression, lighting, face, face, camera, render);
    return render;
  }
};

// The pixels whose shading changed by more than 2 %, and their centroid.
struct Change {
  int pixels = 0;
  cv::Point2d centroid;
};

Change changed(const cv::Mat& render) {
  Change c;
  for (int y = 0; y < render.rows; ++y)
    for (int x = 0; x < render.cols; ++x) {
      if (std::abs(render.at<cv::Vec3f>(y, x)[1] / 0.5f - 1.0f) <= 0.02f) continue;
      ++c.pixels;
      c.centroid += cv::Point2d(x, y);
    }
  if (c.pixels > 0) c.centroid *= 1.0 / c.pixels;
  return c;
}

}  // namespace

TEST(WrinkleShading, ShadesTheTargetsFoldWhereItAppearsSinceTheReference) {
  FACECAP_REQUIRE_MODEL(model);
  const WrinkleCase k(*model);
  const Eigen::VectorXf &neutral = k.neutral, &moved = k.moved;
  WrinkleShading w(skin_mesh(*model), neutral);
  // The first frame (the source's own expression) is the reference: no motion.
  const Change first = changed(k.shade(w, k.flat, neutral));
  EXPECT_EQ(first.pixels, 0);
  // A later frame, farther from the source's expression, has folded.
  const Change later = changed(k.shade(w, k.folded, moved));
  const Vec2f centre = k.camera.project(k.bump_centre);
  const double sigma_px = 900 * 0.4 / k.bump_centre.z();
  std::printf("fold: %d pixels changed, centred at (%.1f, %.1f), the bump at (%.1f, %.1f), sigma %.1f px\n",
              later.pixels, later.centroid.x, later.centroid.y, centre.x(), centre.y(), sigma_px);
  EXPECT_GT(later.pixels, 50);
  EXPECT_LT(later.pixels, 60 * sigma_px * sigma_px);
  EXPECT_LT(std::hypot(later.centroid.x - centre.x(), later.centroid.y - centre.y()), sigma_px);
  // Back to the flat face: the fold is gone again.
  EXPECT_EQ(changed(k.shade(w, k.flat, moved)).pixels, 0);
}

TEST(WrinkleShading, AFoldAlreadyInTheReferenceFrameIsNotDrawnAgain) {
  FACECAP_REQUIRE_MODEL(model);
  const WrinkleCase k(*model);
  const Eigen::VectorXf &neutral = k.neutral, &moved = k.moved;
  WrinkleShading w(skin_mesh(*model), neutral);
  EXPECT_EQ(changed(k.shade(w, k.folded, neutral)).pixels, 0);
  EXPECT_EQ(changed(k.shade(w, k.folded, moved)).pixels, 0);
  // Its going away is motion, and shows.
  EXPECT_GT(changed(k.shade(w, k.flat, moved)).pixels, 50);
}

}  // namespace facecap
