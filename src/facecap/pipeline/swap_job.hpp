#pragma once
// `facecap swap --source PHOTO --target VIDEO -o OUT.mp4` (chapter 6): the
// portrait is reconstructed once (identity, expression, SH lighting, its
// unshaded appearance), the target tracked frame by frame with its lighting,
// and every frame with a face re-rendered with the source's face (face/
// swapper). Frames where the target face is lost pass through unchanged.
// The output carries the target's audio and the synthetic-media marks.
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "facecap/io/video_encoding.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/job_cpu.hpp"
#include "facecap/swap/face_swapper.hpp"

namespace facecap {

struct SourceReconstruction {
  cv::Mat photo;        // the image the appearance comes from
  int frames_used = 1;  // frames the source identity was solved from
  SourceFace face;
  int faces_found = 0;  // faces the detector saw in the photo (the pick chooses which is used)
};

// The source is a photo, or a short video or a folder of photos of one face
// (a burst): then the identity is solved jointly over its first
// `source_frames` frames, as a video's is, and the appearance comes from its
// first frame with a face. Throws facecap::Error naming the file when it
// cannot be read or holds no face.
// `pick`: which face of a photo with several (a group photo).
SourceReconstruction reconstruct_source(const FaceModel& model, const std::string& source, bool quiet = false,
                                        int source_frames = 30, const FacePick& pick = {});

struct SwapJobOptions {
  CaptureOptions capture;
  SwapOptions swap;
  VideoEncoding encoding;  // the output video's (and its matte's preset)
  int source_frames = 30;  // frames of a source video or folder the identity is solved from
  FacePick source_face;    // which face of the source where it shows several (capture.tracker.pick: the target's)
  // --all-faces: target faces (by index in the order found, as track
  // --all-faces numbers them) given a source of their own (`--face-source
  // 1=photo.jpg`: a photo, video or folder, as the source; its largest face)
  // instead of the job's source.
  std::map<int, std::string> face_sources;
  // The swapped performance as an animated glTF (face_animation.hpp): the
  // source's identity at the size the swap gives it, performing the target's
  // keys (pose and expression), textured with the source's harmonised albedo
  // (FaceSwapper::harmonised_texture), and marked as synthetic, with a
  // sidecar GLTF.json; one per shot where the target cuts
  // (shot_animations.hpp). Empty: none.
  std::filesystem::path gltf;
  // The new face's share of each output pixel (SwappedFrame::alpha, after
  // the covers), as a greyscale video or image frame for frame with the
  // output (matte_output.hpp), marked like it. Empty: none.
  std::filesystem::path matte;
  // The whole target captured before the swap starts (one face only), so
  // that the swap's stages run without capture beside them: for `bench swap
  // --tracked-first`. Holds every frame in memory (about 2.8 MB a 720p frame).
  bool track_first = false;
  // Called with each output frame (and the target frame it came from).
  std::function<void(const CapturedFrame& target, const SwappedFrame& result)> on_frame;
  // Each output frame as it is written (before encoding), in order, with
  // --all-faces too: for evals and tests.
  std::function<void(int index, const cv::Mat& image)> on_output_frame;
};

struct SwapJobTimings {
  SwapTimings swap;
  double lighting_ms = 0;     // the target's SH lighting per frame (and its displacements with wrinkles)
  double preparation_ms = 0;  // unshading and moving covers (frame_preparation.hpp), beside the swap
  double source_ms = 0;       // reconstructing the portrait
  int swapped = 0;            // frames with a face
  // CPU time (core/cpu_time.hpp; ms over the run), where the wall times
  // above include waits for a core: the swap's own thread (the swap and
  // its frame's writing), the preparation's and the lighting's threads, the
  // encoder process, and the pool's workers (on every stage's loops, the
  // capture's too, but with track_first, where capture runs first), and
  // all of facecap's threads together (the same share).
  double swap_thread_cpu_ms = 0;
  double preparation_cpu_ms = 0;
  double lighting_cpu_ms = 0;
  JobCpu job_cpu;  // the encoder's, the pool's and facecap's whole
};

struct SwapSummary {
  CaptureSummary target;
  SourceReconstruction source;
  SwapJobTimings timings;
  std::vector<std::filesystem::path> animation_files;  // --gltf: one per shot with a face (shot_animations.hpp)
};

SwapSummary run_swap(const FaceModel& model, const std::string& source_photo, const std::string& target,
                     const std::filesystem::path& output, const SwapJobOptions& options);

struct AllFacesSwapSummary {
  AllFacesSummary target;  // the target's faces, each one's capture, the shared pass
  SourceReconstruction source;
  std::map<int, SourceReconstruction> face_sources;  // SwapJobOptions::face_sources, reconstructed
  SwapJobTimings timings;                            // summed over the faces
  std::vector<int> swapped;                          // per face, the frames swapped (0 for one left as it is)
};

// `swap --all-faces`: the source's face put on every face the target shows
// (face_roster.hpp: those entering later too), each as run_swap puts it on
// one, on one pass, into one output: to replace everyone in a clip, as for
// anonymising bystanders with a consenting person's face. Each face's swap
// changes only its window of the frame; where two windows overlap, the face
// found later is laid over; the matte holds, at each pixel, the largest of
// the faces' alphas. SwapJobOptions::gltf is for one face (an error here);
// capture.tracker.pick and on_frame are not used.
AllFacesSwapSummary run_swap_all_faces(const FaceModel& model, const std::string& source_photo,
                                       const std::string& target, const std::filesystem::path& output,
                                       const SwapJobOptions& options, const AllFacesOptions& all = {});

}  // namespace facecap
