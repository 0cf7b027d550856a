#pragma once
// `facecap transform INPUT --to EMOTION -o OUT.mp4`: expression
// transformation of a talking face (chapter 5). Frames are tracked, their
// weights mapped and lip-corrected (expr/), the face re-rendered with the new
// expression under the frame's pose and lighting, the source mouth interior
// warped to the new lips, the source eyes kept, and the layers blended back
// with a Laplacian pyramid (compose/). The output carries the input's audio
// and the synthetic-media marks.
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "facecap/expr/expression_transform.hpp"
#include "facecap/io/video_encoding.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/face_transform_stream.hpp"
#include "facecap/refine/refiner.hpp"

namespace facecap {

struct TransformJobOptions {
  CaptureOptions capture;
  TransformOptions transform;
  CoverOptions covers;     // what covers a face stays in front of its new expression
  VideoEncoding encoding;  // the output video's (and its matte's preset)
  std::filesystem::path models_dir = default_expression_models_dir();
  std::filesystem::path plot;  // PNG of weight curves (empty: none)
  // The transformed performance as an animated glTF (face_animation.hpp),
  // marked as synthetic like the video (empty: none); one per shot where
  // the input cuts (shot_animations.hpp).
  std::filesystem::path gltf;
  // The re-rendered face's share of each output pixel (layer_blend_mask,
  // before the pyramid), as a greyscale video or image frame for frame with
  // the output (matte_output.hpp), marked like it; with every face, the
  // largest of the faces' shares at each pixel. Empty: none.
  std::filesystem::path matte;
  std::string description;  // for the synthetic mark, e.g. "neutral to happiness"
  // --all-faces: faces (by index in the order found, as track --all-faces
  // numbers them) given an expression of their own (`--face-to 1=sadness`,
  // `--face-schedule 1=keys.txt`) instead of transform.schedule.
  struct FaceExpression {
    ExpressionSchedule schedule;
    std::string description;  // for the synthetic mark, e.g. "neutral to sadness"
  };
  std::map<int, FaceExpression> face_expressions;
  // Each output frame as it is written (before encoding), in order: for evals and tests.
  std::function<void(int index, const cv::Mat& image)> on_frame;
};

struct TransformSummary {
  CaptureSummary capture;
  std::vector<TransformedFrame> frames;  // weights per frame (no images)
  TransformTimings timings;
  std::vector<std::filesystem::path> animation_files;  // --gltf: one per shot with a face (shot_animations.hpp)
};

TransformSummary run_transform(const FaceModel& model, const std::string& input, const std::filesystem::path& output,
                               const TransformJobOptions& options);

struct AllFacesTransformSummary {
  AllFacesSummary capture;  // the faces, each one's capture, the shared pass
  std::vector<std::vector<TransformedFrame>>
      frames;                // per face, from the frame it was found in (none for one left as it is)
  TransformTimings timings;  // summed over the faces; frames: the output's
};

// `transform --all-faces`: every face the input shows (face_roster.hpp), each
// transformed as run_transform transforms one, their layers composited over
// the same frames into one output. TransformJobOptions::gltf and plot are for
// one face (an error here); capture.tracker.pick is not used.
AllFacesTransformSummary run_transform_all_faces(const FaceModel& model, const std::string& input,
                                                 const std::filesystem::path& output,
                                                 const TransformJobOptions& options, const AllFacesOptions& all = {});

// The PNG of the paper's Fig. 5.8: tracked, mapped, lip-corrected and
// smoothed curves of the weights the transformation changed most.
void write_weight_plot(const std::filesystem::path& path, const std::vector<TransformedFrame>& frames,
                       const std::vector<std::string>& names, int curves = 4);

}  // namespace facecap
