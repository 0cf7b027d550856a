#pragma once
// The videos `facecap track --overlay` writes (track_job.hpp): DIR/overlay.mp4,
// the input with the fitted mesh, the detected (green) and fitted (red)
// landmarks and the gaze drawn over it; with --refine also DIR/shaded.mp4, the
// refined finest level shaded grey under the frame's lighting, and
// DIR/heatmap.mp4, the photometric error of the refined surface with the
// recovered albedo and lighting (paper Fig. 4.11). Each keeps the input's
// timing; a lost frame is written undrawn, captioned `lost`.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "facecap/pipeline/track_job.hpp"

namespace facecap {

class VideoWriter;

class TrackVideos {
 public:
  // The names of the files it may write in the output folder (an input
  // must not be one of them).
  static const std::vector<std::string>& file_names();

  TrackVideos(const FaceModel& model, const InputInfo& info, const std::string& input, const std::filesystem::path& dir,
              const TrackOptions& options);
  ~TrackVideos();
  TrackVideos(const TrackVideos&) = delete;
  TrackVideos& operator=(const TrackVideos&) = delete;

  // One frame of each video. `coarse`: the coarse face region in camera
  // space; `ref`, `refiner`: the frame's refinement and the refiner whose
  // hierarchy it is on (null: not refined, drawn dimmed).
  void write(const CapturedFrame& f, const Refinement* ref, const Refiner* refiner, const Positions& coarse,
             const PinholeCamera& camera);
  // Each video completed and renamed into place.
  void finish();

 private:
  void write_refined(const CapturedFrame& f, const Refinement* ref, const Refiner* refiner, const PinholeCamera& camera,
                     double time);

  InputInfo info_;
  std::vector<Polygon> face_polygons_;
  std::unique_ptr<VideoWriter> overlay_, shaded_, heatmap_;
};

}  // namespace facecap
