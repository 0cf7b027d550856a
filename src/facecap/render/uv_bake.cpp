#include "facecap/render/uv_bake.hpp"

#include <opencv2/imgproc.hpp>

#include "facecap/render/uv_raster.hpp"

namespace facecap {

cv::Mat bake_uv_texture(const TriangleMesh& mesh, const Positions& values, int size) {
  const UvTexelMap map = rasterize_uv(mesh, size);
  cv::Mat tex(size, size, CV_8UC3, cv::Scalar::all(0));
  cv::Mat covered(size, size, CV_8U, cv::Scalar(0));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int i = map.index(x, y);
      if (map.triangle[i] < 0) continue;
      const Vec3f c = map.interpolate(mesh.triangles, values, i);
      tex.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(c.z() * 255), cv::saturate_cast<uchar>(c.y() * 255),
                                          cv::saturate_cast<uchar>(c.x() * 255));
      covered.at<uchar>(y, x) = 255;
    }
  }
  // Grow the islands by two texels so that texture filtering does not pull in black.
  for (int i = 0; i < 2; ++i) {
    cv::Mat grown, grown_cover;
    cv::dilate(tex, grown, cv::Mat());
    cv::dilate(covered, grown_cover, cv::Mat());
    grown.copyTo(tex, covered == 0);
    covered = grown_cover;
  }
  return tex;
}

}  // namespace facecap
