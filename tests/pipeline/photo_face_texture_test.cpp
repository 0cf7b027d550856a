#include "facecap/pipeline/photo_face_texture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "facecap/core/error.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/render/uv_raster.hpp"
#include "test_support.hpp"

namespace facecap {

// A real portrait's skin lands in the model's UV layout where the model has
// the features: the brows (just below their landmark vertices, toward the
// eye, as the 300-W annotation marks a brow's upper edge) are darker than the
// face's typical skin, and the lips redder. A flipped or shifted layout, or
// an unshading that lost the colour, fails.
TEST(PhotoFaceTexture, APortraitsBrowsAndLipsLandWhereTheModelHasThem) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(photo, "portrait_obama.jpg");
  const int size = 512;
  const cv::Mat texture = face_texture_from_photo(*model, photo.string(), size);
  ASSERT_EQ(texture.type(), CV_32FC3);
  ASSERT_EQ(texture.rows, size);
  ASSERT_EQ(texture.cols, size);
  double lo = 0, hi = 0;
  cv::minMaxLoc(texture.reshape(1), &lo, &hi);
  EXPECT_GE(lo, 0.0);  // also fails on NaN
  EXPECT_LE(hi, 1.0);

  const std::vector<Vec2f> uv = per_vertex_uvs(model->region_mesh(regions::kFace));
  auto texel = [&](int landmark) { return uv_to_texel(uv[model->landmarks.vertices[landmark]], size); };
  // Mean BGR over a 5x5 patch about a texel position.
  auto colour = [&](const Vec2f& p) {
    const cv::Rect patch(int(std::lround(p.x())) - 2, int(std::lround(p.y())) - 2, 5, 5);
    return cv::mean(texture(patch & cv::Rect(0, 0, size, size)));
  };
  auto luminance = [](const cv::Scalar& c) { return (c[0] + c[1] + c[2]) / 3.0; };
  // The typical skin: the median luminance and redness over the narrow face's vertices.
  std::vector<double> skin_luminance, skin_redness;
  for (int v = 0; v <= regions::kNarrowFace.last_vertex; v += 7) {
    const cv::Scalar c = colour(uv_to_texel(uv[v], size));
    skin_luminance.push_back(luminance(c));
    skin_redness.push_back(c[2] / std::max(c[1], 1e-3));
  }
  auto median = [](std::vector<double> x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x[x.size() / 2];
  };
  const double skin = median(skin_luminance), skin_red = median(skin_redness);
  const float eye_texels = (texel(36) - texel(45)).norm();
  // The middle of each brow (its ends thin out on this face): measured
  // 0.28-0.37 against the skin's 0.55.
  for (int i : {18, 19, 20, 23, 24, 25}) {
    Vec2f eye = Vec2f::Zero();
    for (int k = 0; k < 6; ++k) eye += texel((i < 22 ? 36 : 42) + k) / 6.0f;
    const Vec2f in_brow = texel(i) + 0.04f * eye_texels * (eye - texel(i)).normalized();
    EXPECT_LT(luminance(colour(in_brow)), 0.7 * skin) << "brow point " << i;
  }
  // The middle of each lip, between its outer and inner points: red over
  // green measured 1.60 against the skin's 1.38.
  for (const auto& [outer, inner] : {std::pair{51, 62}, std::pair{57, 66}}) {
    const cv::Scalar lip = colour(0.5f * (texel(outer) + texel(inner)));
    EXPECT_GT(lip[2] / lip[1], 1.1 * skin_red) << "lip between points " << outer << " and " << inner;
  }
}

TEST(PhotoFaceTexture, APhotoWithoutAFaceIsAnErrorNamingIt) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const std::string blank = (dir.path() / "wall.png").string();
  write_image(blank, cv::Mat(240, 320, CV_8UC3, cv::Scalar(120, 130, 140)));
  for (const std::string& photo : {blank, (dir.path() / "missing.jpg").string()}) {
    try {
      face_texture_from_photo(*model, photo, 64);
      ADD_FAILURE() << photo;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(photo), std::string::npos) << e.what();
    }
  }
}

}  // namespace facecap
