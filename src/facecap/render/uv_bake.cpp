#include "facecap/render/uv_bake.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace facecap {

cv::Mat bake_uv_texture(const TriangleMesh& mesh, const Positions& values, int size) {
  cv::Mat tex(size, size, CV_8UC3, cv::Scalar::all(0));
  cv::Mat covered(size, size, CV_8U, cv::Scalar(0));
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    Vec2f p[3];
    for (int k = 0; k < 3; ++k) {
      const Vec2f uv = mesh.uvs[mesh.triangle_uvs[t][k]];
      p[k] = Vec2f(uv.x() * (size - 1), (1.0f - uv.y()) * (size - 1));  // v up in OBJ
    }
    const float area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
    if (std::abs(area) < 1e-8f) continue;
    const int x0 = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(size - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(size - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const float w0 = ((p[1].x() - x) * (p[2].y() - y) - (p[1].y() - y) * (p[2].x() - x)) / area;
        const float w1 = ((p[2].x() - x) * (p[0].y() - y) - (p[2].y() - y) * (p[0].x() - x)) / area;
        const float w2 = 1.0f - w0 - w1;
        if (w0 < -1e-4f || w1 < -1e-4f || w2 < -1e-4f) continue;
        const Vec3f c = w0 * values.col(mesh.triangles[t][0]) + w1 * values.col(mesh.triangles[t][1]) +
                        w2 * values.col(mesh.triangles[t][2]);
        tex.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(c.z() * 255), cv::saturate_cast<uchar>(c.y() * 255),
                                            cv::saturate_cast<uchar>(c.x() * 255));
        covered.at<uchar>(y, x) = 255;
      }
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
