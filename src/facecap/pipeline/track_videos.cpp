#include "facecap/pipeline/track_videos.hpp"

#include "facecap/io/video_writer.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/render/overlay.hpp"
#include "facecap/render/photometric.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr const char* kOverlayVideo = "overlay.mp4";
constexpr const char* kShadedVideo = "shaded.mp4";
constexpr const char* kHeatmapVideo = "heatmap.mp4";

}  // namespace

const std::vector<std::string>& TrackVideos::file_names() {
  static const std::vector<std::string> names = {kOverlayVideo, kShadedVideo, kHeatmapVideo};
  return names;
}

TrackVideos::TrackVideos(const FaceModel& model, const InputInfo& info, const std::string& input, const fs::path& dir,
                         const TrackOptions& options)
    : info_(info), face_polygons_(model.region_polygons(regions::kFace)) {
  const std::string name = fs::path(input).filename().string();
  VideoWriterOptions vo = output_like(info, options.capture.max_frames, options.encoding);
  vo.metadata = {{"comment", "facecap track overlay of " + name}};
  overlay_ = std::make_unique<VideoWriter>(dir / kOverlayVideo, vo);
  if (options.refine) {
    vo.metadata["comment"] = "facecap refined geometry (shaded) of " + name;
    shaded_ = std::make_unique<VideoWriter>(dir / kShadedVideo, vo);
    vo.metadata["comment"] = "facecap photometric error heat map of " + name;
    heatmap_ = std::make_unique<VideoWriter>(dir / kHeatmapVideo, vo);
  }
}

TrackVideos::~TrackVideos() = default;

void TrackVideos::write(const CapturedFrame& f, const Refinement* ref, const Refiner* refiner, const Positions& coarse,
                        const PinholeCamera& camera) {
  cv::Mat canvas = f.image.clone();
  if (f.status != TrackStatus::kLost) {
    draw_wireframe(canvas, coarse, face_polygons_, camera, cv::Scalar(255, 200, 80));
    draw_landmarks(canvas, f.fit.observed, cv::Scalar(0, 255, 0));
    draw_landmarks(canvas, f.fit.fitted, cv::Scalar(0, 0, 255), 1);
    for (int eye = 0; eye < 2; ++eye) {
      const std::optional<EyeGaze>& g = f.fit.gaze.eyes[eye];
      if (g)
        draw_gaze(canvas, f.fit.irises[eye]->centre, f.fit.irises[eye]->radius, g->camera_iris, g->camera_direction,
                  4.0, camera, cv::Scalar(0, 220, 255));
    }
  }
  draw_caption(canvas, "frame " + std::to_string(f.index) + "  " + to_string(f.status));
  const double time = output_time(info_, f.index, f.time);
  overlay_->write(canvas, time);
  if (shaded_) write_refined(f, ref, refiner, camera, time);
}

// shaded.mp4 and heatmap.mp4: the input dimmed, and over it, where the frame
// was refined, the refined surface shaded grey / its photometric error.
void TrackVideos::write_refined(const CapturedFrame& f, const Refinement* ref, const Refiner* refiner,
                                const PinholeCamera& camera, double time) {
  cv::Mat shaded = f.image * 0.3;
  cv::Mat heat = f.image * 0.4;
  if (f.status != TrackStatus::kLost && ref != nullptr && refiner != nullptr) {
    const std::vector<Triangle>& tris = refiner->hierarchy().level(ref->levels - 1).triangles;
    RasterBuffers buffers;
    buffers.resize(f.image.cols, f.image.rows);
    rasterize(ref->positions, tris, camera, buffers);
    cv::Mat render(f.image.rows, f.image.cols, CV_32FC3, cv::Scalar::all(0));
    const Positions grey = Positions::Constant(3, ref->positions.cols(), 0.75f);
    shade_lambertian(buffers, tris, grey, ref->normals, ref->lighting, render);
    cv::Mat render8;
    render.convertTo(render8, CV_8UC3, 255.0);
    cv::Mat mask(f.image.rows, f.image.cols, CV_8U, cv::Scalar(0));
    for (int y = 0; y < buffers.height; ++y)
      for (int x = 0; x < buffers.width; ++x) mask.at<uchar>(y, x) = buffers.covered(x, y) ? 255 : 0;
    render8.copyTo(shaded, mask);
    heat = photometric_error(f.image, ref->positions, masked_triangles(tris, ref->data_mask), ref->normals, ref->albedo,
                             ref->lighting, camera, true)
               .heat_map;
  }
  draw_caption(shaded, "frame " + std::to_string(f.index) + "  refined geometry");
  draw_caption(heat, "frame " + std::to_string(f.index) + "  photometric error (red = 40 levels)");
  shaded_->write(shaded, time);
  heatmap_->write(heat, time);
}

void TrackVideos::finish() {
  for (VideoWriter* w : {overlay_.get(), shaded_.get(), heatmap_.get()})
    if (w) w->finish();
}

}  // namespace facecap
