#include "facecap/pipeline/face_matte.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "facecap/core/mesh.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

// The mean face's region in model space, in millimetres.
Positions mean_face_mm(const FaceModel& model) {
  const Eigen::VectorXf shape = model.identity_shape(Eigen::VectorXf(), regions::kFace);
  return 10.0f * Eigen::Map<const Positions>(shape.data(), 3, regions::kFace.num_vertices());
}

}  // namespace

// On the mean face: the rest of the face region (scalp, ears, neck) is left
// to the footage, the inner face (brows, eyes, nose, lips: iBUG 17-67, the
// eye and mouth holes' rims among them) shows whole, and the narrow face's
// outer edge fades over the feather's width, by no more than smoothstep's
// steepest slope between neighbours.
TEST(FaceMatte, TheNarrowFaceShowsWithAFeatheredOuterEdge) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXf matte = narrow_face_matte(*model);
  ASSERT_EQ(matte.size(), regions::kFace.num_vertices());
  const int narrow = regions::kNarrowFace.num_vertices();
  EXPECT_EQ(matte.tail(matte.size() - narrow).cwiseAbs().maxCoeff(), 0.0f);
  for (int landmark = 17; landmark < 68; ++landmark)
    EXPECT_EQ(matte[model->landmarks.vertices[size_t(landmark)]], 1.0f) << "landmark " << landmark;

  const Positions mm = mean_face_mm(*model);
  const TriangleMesh mesh = model->region_mesh(regions::kFace);
  const VertexAdjacency ring = vertex_adjacency(mesh.triangles, mesh.num_vertices);
  // Each narrow vertex's straight-line distance to the nearest vertex off the
  // narrow face: a path along the surface is no shorter.
  int fading = 0, near_the_edge = 0, near_and_whole = 0;
  double steepest = 0;
  for (int v = 0; v < narrow; ++v) {
    float nearest = 1e9f;
    for (int w = narrow; w < mesh.num_vertices; ++w) nearest = std::min(nearest, (mm.col(w) - mm.col(v)).norm());
    if (matte[v] < 1) {
      ++fading;
      EXPECT_LT(nearest, kFaceMatteFeatherMm) << v;  // fading only within the feather of the edge
    }
    if (nearest < 0.5f * kFaceMatteFeatherMm) {
      ++near_the_edge;
      near_and_whole += matte[v] == 1.0f;
    }
    for (int k = ring.offsets[size_t(v)]; k < ring.offsets[size_t(v) + 1]; ++k) {
      const int w = ring.indices[size_t(k)];
      steepest = std::max(steepest, double(std::abs(matte[v] - matte[w]) / (mm.col(v) - mm.col(w)).norm()));
    }
  }
  std::printf("%d of %d narrow-face vertices fade; steepest change %.4f per mm (smoothstep's most: %.4f)\n", fading,
              narrow, steepest, 1.5 / kFaceMatteFeatherMm);
  EXPECT_GT(fading, 100);
  EXPECT_EQ(near_and_whole, 0) << "of " << near_the_edge;  // within half the feather, none whole yet
  EXPECT_LE(steepest, 1.5 / kFaceMatteFeatherMm * 1.0001);
}

// face_matte.png's texels hold the vertices' matte where a renderer reads
// them: sampled bilinearly at each vertex's UV (texel x's centre at
// (x + 0.5) / size, v up), the image gives the vertex's value.
TEST(FaceMatte, TheImageHoldsEachVertexsMatteAtItsUv) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXf matte = narrow_face_matte(*model);
  const cv::Mat image = face_matte_image(*model, 1024);
  ASSERT_EQ(image.type(), CV_8U);
  ASSERT_EQ(image.size(), cv::Size(1024, 1024));
  const TriangleMesh mesh = model->region_mesh(regions::kFace);
  const std::vector<Vec2f> uv = per_vertex_uvs(mesh);
  std::vector<double> error;
  for (int v = 0; v < mesh.num_vertices; ++v) {
    cv::Mat sample;
    cv::getRectSubPix(image, cv::Size(1, 1),
                      cv::Point2f(uv[size_t(v)].x() * 1024 - 0.5f, (1 - uv[size_t(v)].y()) * 1024 - 0.5f), sample,
                      CV_32F);
    error.push_back(std::abs(sample.at<float>(0, 0) / 255.0 - matte[v]));
  }
  const double median_error = median(error), largest = *std::max_element(error.begin(), error.end());
  std::printf("image against the vertices' matte: median %.4f, largest %.4f\n", median_error, largest);
  EXPECT_LT(median_error, 0.002);
  EXPECT_LT(largest, 0.03);  // measured 0.016, where the matte bends
}

}  // namespace facecap
