#pragma once
// An input's frames with several faces' layers composited over them, handed
// on in frame order once every face the frame waits for has given its layer
// or said it has none (`transform --all-faces`: each face's stream runs on a
// thread of its own, with a delay of its own). A face's layer may come before
// or after its frame.
#include <functional>
#include <map>
#include <mutex>
#include <optional>

#include <opencv2/core.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/pipeline/face_roster.hpp"

namespace facecap {

class LayeredFrames {
 public:
  // Called in frame order, each frame once, under the object's lock (on
  // whichever thread completed the frame).
  using Write = std::function<void(const cv::Mat& image, int index, double time)>;
  // How a face's layer goes over the frame (the transformation blends its
  // re-rendered face in; a swap's layer is already blended, and is copied).
  using Composite = std::function<void(cv::Mat& frame, const FaceLayer& layer)>;
  LayeredFrames(Write write, Composite composite) : write_(std::move(write)), composite_(std::move(composite)) {}
  // Also hands on each frame's matte (8-bit, frame-sized: at each pixel the
  // largest layer_share() of the faces' layers there), just before the frame.
  // Set it before the first frame.
  void on_matte(Write matte) { matte_ = std::move(matte); }

  // Frame `index` (frames come in increasing order), waiting for `faces`
  // faces' word; one waiting for none is handed on at once.
  void add_frame(int index, double time, const cv::Mat& image, int faces);
  // Face `face`'s word on frame `index`: its layer, or none (null).
  void add_layer(int index, int face, const FaceLayer* layer);
  // Throws facecap::Error where a frame is still waiting (a face that never
  // gave its word on it).
  void finish();

  int written() const;
  double composite_ms() const;  // compositing, summed

 private:
  struct Entry {
    std::optional<cv::Mat> image;  // once the frame itself came
    double time = 0;
    int faces = 0;                    // the faces it waits for
    int heard = 0;                    // the faces whose word came
    std::map<int, FaceLayer> layers;  // by face, composited in that order
  };
  void write_ready();  // with mutex_ held

  Write write_, matte_;
  Composite composite_;
  mutable std::mutex mutex_;
  std::map<int, Entry> entries_;
  int written_ = 0;
  double composite_ms_ = 0;
};

// An edit of every face (transform and swap --all-faces): the input's faces
// captured on one pass (face_roster.hpp, with the frames' images), every
// frame handed to `frames`, waiting for the faces in it. `edit_face` makes
// the sink for each face to edit, which gives `frames` its word on each of
// that face's frames under FoundFace::index; a face in
// AllFacesOptions::unedited is followed and passed through (its sink says
// "no layer").
using EditFaceSink = std::function<FrameSink(const FoundFace& face)>;
AllFacesSummary capture_all_faces_into(LayeredFrames& frames, const FaceModel& model, FrameSource& source,
                                       CaptureOptions capture, const AllFacesOptions& all,
                                       const EditFaceSink& edit_face);

}  // namespace facecap
