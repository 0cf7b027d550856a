#pragma once
// `facecap track --all-faces`: every face the first frame with a face shows
// (of the first 300: a video may open on black or a title), each
// captured into a folder of its own (DIR/face_<k>, k from 0, left to right),
// as `track --face X,Y` at that face's centre would capture it, and
// DIR/faces.json listing them. One capture per face: they share nothing but
// the input, and each takes the time of a capture. Folders face_<k> of an
// earlier run with more faces are removed.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/pipeline/track_job.hpp"

namespace facecap {

struct EachFaceSummary {
  std::vector<Box> faces;          // in the first frame with a face, left to right
  int face_frame = -1;             // that frame's index
  std::vector<TrackSummary> runs;  // one per face, in that order
};

// Throws facecap::Error for a camera (it cannot be read once per face) and
// where the first 300 frames show no face, before anything is written.
EachFaceSummary run_track_each_face(const FaceModel& model, const std::string& input,
                                    const std::filesystem::path& output_dir, const TrackOptions& options);

// The folder of face `k` (DIR/face_<k>).
std::filesystem::path face_folder(const std::filesystem::path& output_dir, int k);

}  // namespace facecap
