#include "facecap/pipeline/layered_frames.hpp"

#include <chrono>

#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"

namespace facecap {

void LayeredFrames::add_frame(int index, double time, const cv::Mat& image, int faces) {
  std::lock_guard lock(mutex_);
  Entry& e = entries_[index];
  e.image = image;
  e.time = time;
  e.faces = faces;
  write_ready();
}

void LayeredFrames::add_layer(int index, int face, const FaceLayer* layer) {
  std::lock_guard lock(mutex_);
  Entry& e = entries_[index];
  ++e.heard;
  if (layer) e.layers.emplace(face, *layer);
  write_ready();
}

// Frames reach entries_ in order (a face's word on a frame never comes
// before the frames before it were added), so the first entry is the next
// to write.
void LayeredFrames::write_ready() {
  while (!entries_.empty()) {
    auto first = entries_.begin();
    Entry& e = first->second;
    if (!e.image || e.heard < e.faces) return;
    cv::Mat out = *e.image;
    if (!e.layers.empty()) {
      const auto t0 = std::chrono::steady_clock::now();
      out = e.image->clone();
      for (const auto& [face, layer] : e.layers) composite_(out, layer);
      composite_ms_ += ms_since(t0);
    }
    if (matte_) {
      cv::Mat matte(out.size(), CV_8U, cv::Scalar(0));
      for (const auto& [face, layer] : e.layers) {
        cv::Mat window = matte(layer.box);
        cv::max(window, layer_share(layer), window);
      }
      matte_(matte, first->first, e.time);
    }
    write_(out, first->first, e.time);
    ++written_;
    entries_.erase(first);
  }
}

void LayeredFrames::finish() {
  std::lock_guard lock(mutex_);
  if (!entries_.empty())
    throw Error("internal: frame " + std::to_string(entries_.begin()->first) + " still waits for a face's layer");
}

int LayeredFrames::written() const {
  std::lock_guard lock(mutex_);
  return written_;
}

double LayeredFrames::composite_ms() const {
  std::lock_guard lock(mutex_);
  return composite_ms_;
}

AllFacesSummary capture_all_faces_into(LayeredFrames& frames, const FaceModel& model, FrameSource& source,
                                       CaptureOptions capture, const AllFacesOptions& all,
                                       const EditFaceSink& edit_face) {
  capture.keep_images = true;
  const InputInfo info = source.info();
  return run_capture_all_faces(
      model, source, capture, all,
      [&](const FoundFace& face, const InputInfo&) -> FrameSink {
        if (all.unedited.contains(face.index))  // followed, and passed through
          return [&frames, k = face.index](const CapturedFrame& f) { frames.add_layer(f.index, k, nullptr); };
        return edit_face(face);
      },
      [&](const DecodedFrame& d, int faces) {
        frames.add_frame(d.frame.index, d.frame.time, image_or_black(d.frame, info), faces);
      });
}

}  // namespace facecap
