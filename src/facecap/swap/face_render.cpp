#include "facecap/swap/face_render.hpp"

#include <algorithm>

#include "facecap/compose/face_reshading.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/core/uv_texel.hpp"
#include "facecap/render/outline_distance.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/swap/silhouette_fade.hpp"

namespace facecap {

cv::Mat render_swapped_face(const TriangleMesh& skin, const TextureLevels& texture, const Positions& points,
                            const Positions& normals, const PinholeCamera& frame_camera, const PinholeCamera& window,
                            cv::Size size, const ShCoeffs& lighting, const FaceLight& light,
                            float silhouette_fade_start, cv::Mat& alpha) {
  RasterBuffers buffers;
  buffers.resize(size.width, size.height);
  rasterize(points, skin.triangles, window, buffers);
  cv::Mat render(size, CV_32FC3, cv::Scalar::all(0));
  alpha = cv::Mat(size, CV_32F, cv::Scalar(0));
  const int texture_size = texture.level(0).cols;
  // The texture at the density the face is seen at (texture_levels.hpp).
  const float lod = texture.lod_for(texels_per_pixel(skin, points, frame_camera, texture_size));
  // The silhouette fade's band: a tenth of the face's width (a cylinder's
  // surface turns 53 degrees from the view ray, where the fade ends, a
  // tenth of its width inside its outline).
  const cv::Mat outline_px = outline_distance(buffers);
  cv::Mat turned(size, CV_32F, cv::Scalar(1));  // undrawn: no surface facing the camera
  const SilhouetteFade fade{silhouette_fade_start,
                            std::max(2.0f, 0.1f * float(projected_bounds(points, frame_camera).width))};
  const cv::Mat& gains = light.residual_gains;
  const cv::Mat& ratio_gains = light.expression_gains;
  const Vec3f tint = light.tint;
  // The UV of the pixel at buffer index i (drawn).
  const auto pixel_uv = [&](size_t i) { return uv_at(skin, buffers.triangle[i], buffers.bary[i]); };
  constexpr int kPixelsAhead = 8;
  parallel_for(
      size.height,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* colour = render.ptr<cv::Vec3f>(y);
          float* a = alpha.ptr<float>(y);
          const float* outline = outline_px.ptr<float>(y);
          float* turn = turned.ptr<float>(y);
          const size_t row = size_t(y) * size.width;
          for (int x = 0; x < size.width; ++x) {
            const size_t i = row + x;
            // The texture a few pixels on, asked for now (TextureLevels::prefetch).
            if (x + kPixelsAhead < size.width && buffers.triangle[i + kPixelsAhead] >= 0) {
              const Vec2f ahead = uv_to_texel(pixel_uv(i + kPixelsAhead), texture_size);
              texture.prefetch(lod, ahead.x(), ahead.y());
            }
            const int tri = buffers.triangle[i];
            if (tri < 0) continue;
            const Vec2f coord = pixel_uv(i);
            const Vec2f texel = uv_to_texel(coord, texture_size);
            const cv::Vec4f s = texture.sample<4>(lod, texel.x(), texel.y());
            const Vec3f normal = interpolate(buffers, skin.triangles, normals, i).normalized();
            const Vec3f n = to_viewer_frame(normal);
            const float shade = 255.0f * std::max(0.0f, sh_shade(lighting, n.x(), n.y(), n.z()));
            cv::Vec3f lit(shade * tint[0], shade * tint[1], shade * tint[2]);
            if (!gains.empty()) {
              const Vec2f g = uv_to_texel(coord, gains.cols);
              lit = lit.mul(sample_bilinear_channels<3>(gains, g.x(), g.y()));
            }
            if (!ratio_gains.empty()) {
              const Vec2f r = uv_to_texel(coord, ratio_gains.cols);
              if (ratio_gains.channels() == 3)
                lit = lit.mul(sample_bilinear_channels<3>(ratio_gains, r.x(), r.y()));
              else
                lit *= sample_bilinear_channels<1>(ratio_gains, r.x(), r.y())[0];
            }
            colour[x] = cv::Vec3f(s[0] * lit[0], s[1] * lit[1], s[2] * lit[2]);
            const Vec3f ray = interpolate(buffers, skin.triangles, points, i).normalized();
            turn[x] = fade.turned(-normal.dot(ray));
            a[x] = s[3] * fade.alpha(turn[x], outline[x]);
          }
        }
      },
      16);
  soften_turned_away(render, turned, outline_px, fade);
  return render;
}

}  // namespace facecap
