#include "facecap/pipeline/swap_job.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/io/edit_output.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/matte_output.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/face_swap_stream.hpp"
#include "facecap/pipeline/layered_frames.hpp"
#include "facecap/pipeline/photo_face_texture.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/shot_animations.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A swap's captures, of its source and its target: their landmarks as one
// pass of the cascade finds them, as the swap was tuned with. Handed the
// mirror average (FaceTrackerOptions::mirror_average), the self-swaps came
// out further from their videos (`eval swap --self`, mean: address_720p_a
// 4.21 -> 4.43, emotions_pexels 11.11 -> 11.52, with the source photo's
// landmarks averaged and the target's not) and the cover a hand leaves
// behind lingered (SwapJob.AHandOfTheSkinsOwnColourStaysInFront, four
// frames after the hand has gone: 2.4 % of the face against 0.7 %).
CaptureOptions swap_capture(CaptureOptions capture = {}) {
  capture.tracker.mirror_average = false;
  return capture;
}

}  // namespace

SourceReconstruction reconstruct_source(const FaceModel& model, const std::string& source, bool quiet,
                                        int source_frames, const FacePick& pick) {
  SourceReconstruction r;
  if (!fs::exists(source)) throw Error("source not found: " + source);
  // One decode and one capture of the source: the detector's full-frame search
  // (which counts the faces), the landmarks of the picked one, the fit (a still
  // image's, or a video's identity over the burst).
  std::unique_ptr<FrameSource> input;
  try {
    input = open_input(source);
  } catch (const Error&) {
  }
  if (!input || input->info().kind == InputKind::kCamera)
    throw Error("cannot read the source " + source + " (not a photo, a video or a folder of photos, or corrupt)");
  const bool still = input->info().kind == InputKind::kImage;
  if (!still && source_frames < 1) throw Error("--source-frames must be at least 1");
  CaptureOptions capture = swap_capture();
  capture.quiet = true;
  capture.keep_images = true;
  // The source is one face by the user's word: photos of it taken apart
  // (other rooms, other days) are not shot cuts to solve apart.
  capture.shot_cuts = false;
  capture.tracker.pick = pick;
  if (!still) capture.max_frames = source_frames;
  std::optional<CapturedFrame> fit;
  const CaptureSummary summary = run_capture(model, *input, capture, [&](const CapturedFrame& f) {
    r.faces_found = std::max(r.faces_found, f.faces_seen);
    if (!fit && f.status != TrackStatus::kLost) fit = f;
  });
  const std::string what = still ? "the source photo " : "the source ";
  if (r.faces_found == 0) throw Error("no face found in " + what + source);
  if (const std::string note = damaged_input_note(summary, "the source " + source); !note.empty() && !quiet) {
    std::fprintf(stderr, "facecap: %s\n", note.c_str());
  }
  if (r.faces_found > 1 && !quiet) {
    std::fprintf(stderr, "facecap: %d faces in %s; using the %s (--source-face chooses which)\n", r.faces_found,
                 source.c_str(), describe(pick).c_str());
  }
  if (!fit) throw Error("no face could be fitted in " + what + source);
  r.frames_used = summary.identity.frames_used;
  r.photo = fit->image;
  SourceFace& s = r.face;
  s.identity = fit->identity.identity.cast<float>();
  s.expression = fit->fit.expression;
  s.camera = PinholeCamera::centered(fit->fit.focal, r.photo.cols, r.photo.rows);
  s.camera_points = to_camera(model.evaluate(s.identity, s.expression, regions::kFace), fit->fit.pose);
  s.lighting = face_lighting_of_frame(model, r.photo, s.camera_points, s.camera);
  return r;
}

namespace {

// The swapped face as face_animation() writes it: the source's whole head
// placed as the swap places its face (at the target's size), its harmonised
// texture on the face part, and the marks in asset.extras.
GltfAnimatedMesh swapped_animation(const FaceModel& model, const FaceSwapper& swapper, const SourceFace& source,
                                   const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera,
                                   const SyntheticMark& mark) {
  FaceAnimationRest rest = identity_rest(model, source.identity);
  if (const std::optional<SizeMatch> size = swapper.size_match()) {
    const Positions placed = size->apply(Eigen::Map<const Positions>(rest.head.data(), 3, model.num_vertices));
    rest.head = Eigen::Map<const Eigen::VectorXf>(placed.data(), placed.size());
    rest.blend_shape_scale = float(size->scale);
  }
  GltfAnimatedMesh glb = face_animation(model, rest, keys, camera);
  const cv::Mat texture = swapper.harmonised_texture();
  if (!texture.empty()) glb.primitives.front().base_colour_png = encode_png(texture);
  glb.asset_extras["model"] =
      "ICT Face Model Light (ICT-FaceKit, MIT): face region, mouth and eyes, the source's identity";
  glb.asset_extras.merge(synthetic_metadata(mark));
  return glb;
}

}  // namespace

namespace {

// What a swap does before the target's frames: unwritable outputs and a bad
// target fail first (before the source's fit), then the source is
// reconstructed and the marks made.
struct SwapSetup {
  std::unique_ptr<FrameSource> input;
  InputInfo info;
  SourceReconstruction source;
  std::map<int, SourceReconstruction> face_sources;  // SwapJobOptions::face_sources
  double source_ms = 0;
  SyntheticMark mark;
};

SwapSetup prepare_swap(const FaceModel& model, const std::string& source_photo, const std::string& target,
                       const fs::path& output, const SwapJobOptions& options) {
  std::vector<std::string> inputs = {source_photo, target};
  for (const auto& [face, photo] : options.face_sources) {
    if (face < 0) throw Error("a face's index must be 0 or more, not " + std::to_string(face));
    inputs.push_back(photo);
  }
  ensure_writable_file(fs::absolute(output));
  ensure_not_an_input(output, inputs);
  if (!options.gltf.empty()) {
    ensure_writable_file(fs::absolute(options.gltf));
    ensure_not_an_input(options.gltf, inputs);
  }
  SwapSetup s;
  s.input = open_input(target, options.capture.start_seconds);
  s.info = s.input->info();
  check_edit_output(output, s.info.kind);  // a video, or an image for a photo target
  if (!options.matte.empty()) check_matte_output(options.matte, output, s.info.kind, inputs);
  const auto t0 = std::chrono::steady_clock::now();
  s.source = reconstruct_source(model, source_photo, options.capture.quiet, options.source_frames, options.source_face);
  // Each other source once, however many faces take it.
  std::map<std::string, SourceReconstruction> by_photo;
  for (const auto& [face, photo] : options.face_sources) {
    auto it = by_photo.find(photo);
    if (it == by_photo.end())
      it =
          by_photo.emplace(photo, reconstruct_source(model, photo, options.capture.quiet, options.source_frames)).first;
    s.face_sources[face] = it->second;
  }
  s.source_ms = ms_since(t0);

  SyntheticMark& mark = s.mark;
  mark.kind = "face-swap";
  mark.description = std::string("The face in this ") + (s.info.kind == InputKind::kImage ? "image" : "video") +
                     " was replaced by facecap with the face from " + fs::path(source_photo).filename().string();
  for (const auto& [face, photo] : options.face_sources)
    mark.description += "; face " + std::to_string(face) + " with the face from " + fs::path(photo).filename().string();
  mark.description += ".";
  mark.sources = inputs;
  mark.parameters = {{"appearance_frames", std::to_string(options.swap.appearance_frames)},
                     {"warp_background", options.swap.warp_background ? "true" : "false"},
                     {"keep_occluders", options.swap.keep_occluders ? "true" : "false"},
                     {"moving_covers", options.swap.keep_occluders && options.swap.moving_covers ? "true" : "false"},
                     {"match_grade", options.swap.match_grade ? "true" : "false"},
                     {"match_target_size", options.swap.match_target_size ? "true" : "false"},
                     {"mirror_source", options.swap.mirror_source ? "true" : "false"},
                     {"follow_light_colour", options.swap.follow_light_colour ? "true" : "false"},
                     {"residual_shading_mm", std::to_string(options.swap.residual_shading_mm)},
                     {"expression_ratio", options.swap.expression_ratio ? "true" : "false"},
                     {"photo_detail_gain", std::to_string(options.swap.photo_detail_gain)},
                     {"source_frames_used", std::to_string(s.source.frames_used)},
                     {"target_start_seconds", std::to_string(start_time(s.info))}};
  for (const auto& [face, photo] : options.face_sources)
    mark.parameters["face_" + std::to_string(face) + "_source"] = photo;
  return s;
}

VideoWriterOptions marked_output(const InputInfo& info, const SwapJobOptions& options, const SyntheticMark& mark) {
  VideoWriterOptions vo = output_like(info, options.capture.max_frames, options.encoding);
  vo.metadata = synthetic_metadata(mark);
  return vo;
}

// The pixels a swap changed, as a layer over the frame: its window, and
// there the swapped pixels wherever they differ from the frame's; with
// `share`, the new face's alpha too (for a matte).
FaceLayer changed_pixels(const cv::Mat& frame, const SwappedFrame& swapped, bool share) {
  FaceLayer layer;
  layer.box = swapped.window;
  if (layer.box.area() == 0) return layer;
  layer.colour = swapped.image(layer.box).clone();
  cv::Mat difference;
  cv::absdiff(layer.colour, frame(layer.box), difference);
  cv::Mat channels[3];
  cv::split(difference, channels);
  layer.mask = (channels[0] | channels[1] | channels[2]) > 0;
  if (share) swapped.alpha.convertTo(layer.share, CV_8U, 255.0);
  return layer;
}

// A finished stream's timings added to `sum` (--all-faces sums its faces').
void add_stream_timings(SwapJobTimings& sum, const FaceSwapStream& stream) {
  const SwapTimings& t = stream.timings();
  sum.swap.appearance_ms += t.appearance_ms;
  sum.swap.render_ms += t.render_ms;
  sum.swap.warp_ms += t.warp_ms;
  sum.swap.blend_ms += t.blend_ms;
  sum.swap.wrinkle_ms += t.wrinkle_ms;
  sum.swap.wrinkle_setup_ms += t.wrinkle_setup_ms;
  sum.swap.ratio_ms += t.ratio_ms;
  sum.swap.occlusion_ms += t.occlusion_ms;
  sum.swap.flow_frames += t.flow_frames;
  sum.swapped += stream.swapped();
  const RefineStageTimings& stage = stream.stage_timings();
  sum.lighting_ms += stage.refine_ms;
  sum.preparation_ms += stage.prepare_ms;
  sum.swap_thread_cpu_ms += stage.consumer_cpu_ms;
  sum.preparation_cpu_ms += stage.prepare_cpu_ms;
  sum.lighting_cpu_ms += stage.refine_cpu_ms;
}

}  // namespace

SwapSummary run_swap(const FaceModel& model, const std::string& source_photo, const std::string& target,
                     const fs::path& output, const SwapJobOptions& options) {
  if (!options.face_sources.empty()) throw Error("a source per face (--face-source) needs --all-faces");
  SwapSetup setup = prepare_swap(model, source_photo, target, output, options);
  SwapSummary summary;
  summary.source = std::move(setup.source);
  summary.timings.source_ms = setup.source_ms;
  const InputInfo& info = setup.info;
  const SyntheticMark& mark = setup.mark;
  JobCpuClock cpu;
  EditOutput writer(output, info.kind, marked_output(info, options, mark));
  std::optional<MatteOutput> matte;
  if (!options.matte.empty()) matte.emplace(options.matte, output, info.kind, marked_output(info, options, mark), mark);

  std::optional<ShotAnimations> animations;
  FaceSwapStream stream(model, summary.source.photo, summary.source.face, options.swap,
                        [&](const CapturedFrame& f, const SwappedFrame* swapped) {
                          if (swapped && animations)
                            append_animation_key(animations->keys(f.shot, f.identity), has_timeline(info), f.index,
                                                 f.time, f.fit.pose, f.fit.expression, key_gaze(f.fit.gaze));
                          const cv::Mat& out = swapped ? swapped->image : f.image;
                          const double time = output_time(info, f.index, f.time);
                          writer.write(out, time);
                          if (matte)
                            matte->write(swapped ? swapped->alpha : cv::Mat(), swapped ? swapped->window : cv::Rect(),
                                         f.image.size(), time);
                          if (options.on_output_frame) options.on_output_frame(f.index, out);
                          if (options.on_frame) options.on_frame(f, swapped ? *swapped : SwappedFrame{f.image, {}, {}});
                        });
  // --gltf: one file per shot, each with the swapper's placement and
  // texture for that shot and the shot's focal length.
  stream.on_shot_end([&] {
    if (animations) animations->end_shot();
  });
  if (!options.gltf.empty()) {
    animations.emplace(
        options.gltf,
        [&](const ShotOutput& out, const ShotKeys& shot) {
          GltfAnimatedMesh glb = swapped_animation(model, stream.swapper(), summary.source.face, shot.keys,
                                                   {shot.identity.focal, info.width, info.height}, mark);
          glb.animation_name = shot_animation_name(
              fs::path(target).stem().string() + " (face from " + fs::path(source_photo).filename().string() + ")",
              shot.shot);
          write_glb(out.write_to, glb);
          write_synthetic_sidecar(out.file, mark, out.sidecar_to);
        },
        std::vector<std::string>{source_photo, target});
  }
  CaptureOptions capture = swap_capture(options.capture);
  capture.keep_images = true;
  std::vector<CapturedFrame> tracked;  // with track_first: the whole target, swapped once captured
  summary.target = run_capture(model, *setup.input, capture, [&](const CapturedFrame& f) {
    if (options.track_first)
      tracked.push_back(f);
    else
      stream.push(f);
  });
  if (options.track_first) cpu.restart();  // the swap's share alone
  for (const CapturedFrame& f : tracked) stream.push(f);
  stream.finish();
  add_stream_timings(summary.timings, stream);
  if (summary.target.frames == 0) throw Error("no frames could be read from " + target);
  // A copy of the input marked as a swap would be neither: nothing is written.
  if (summary.timings.swapped == 0) throw Error(no_face_error(target, summary.target.damage, "nothing to swap"));
  writer.finish();
  summary.timings.job_cpu = cpu.taken(writer.encoder_cpu_ms());
  write_synthetic_sidecar(output, mark);
  if (matte) matte->finish();
  if (animations) summary.animation_files = animations->finish();
  return summary;
}

AllFacesSwapSummary run_swap_all_faces(const FaceModel& model, const std::string& source_photo,
                                       const std::string& target, const fs::path& output, const SwapJobOptions& options,
                                       const AllFacesOptions& all) {
  if (!options.gltf.empty()) throw Error("--gltf is for one face: it cannot be used with --all-faces");
  if (options.track_first) throw Error("--tracked-first is for one face: it cannot be used with --all-faces");
  for (const auto& [face, photo] : options.face_sources) {
    if (all.unedited.contains(face))
      throw Error("face " + std::to_string(face) + " is both left as it is (--leave-faces) and given a source");
  }
  SwapSetup setup = prepare_swap(model, source_photo, target, output, options);
  AllFacesSwapSummary summary;
  summary.source = std::move(setup.source);
  summary.face_sources = std::move(setup.face_sources);
  summary.timings.source_ms = setup.source_ms;
  const InputInfo& info = setup.info;
  SyntheticMark& mark = setup.mark;
  mark.parameters["faces"] = "all";
  const JobCpuClock cpu;
  EditOutput writer(output, info.kind, marked_output(info, options, mark));
  std::optional<MatteOutput> matte;
  if (!options.matte.empty()) matte.emplace(options.matte, output, info.kind, marked_output(info, options, mark), mark);

  // Each face's changed pixels, laid over the frame as they are: each swap
  // has blended its face into the frame already.
  LayeredFrames frames(
      [&](const cv::Mat& image, int index, double time) {
        writer.write(image, output_time(info, index, time));
        if (options.on_output_frame) options.on_output_frame(index, image);
      },
      [](cv::Mat& frame, const FaceLayer& layer) { layer.colour.copyTo(frame(layer.box), layer.mask); });
  if (matte)
    frames.on_matte([&](const cv::Mat& image, int index, double time) {
      matte->write(image, cv::Rect({0, 0}, image.size()), image.size(), output_time(info, index, time));
    });
  // One stream per face swapped (by FoundFace::index), each on its thread.
  // Declared after `frames`, so that their threads end before it goes.
  std::map<int, std::unique_ptr<FaceSwapStream>> streams;
  summary.target = capture_all_faces_into(
      frames, model, *setup.input, swap_capture(options.capture), all, [&](const FoundFace& found) -> FrameSink {
        auto& stream = streams[found.index];
        const auto own = summary.face_sources.find(found.index);
        const SourceReconstruction& source = own != summary.face_sources.end() ? own->second : summary.source;
        stream = std::make_unique<FaceSwapStream>(
            model, source.photo, source.face, options.swap,
            [&frames, k = found.index, share = matte.has_value()](const CapturedFrame& f, const SwappedFrame* swapped) {
              if (!swapped) {
                frames.add_layer(f.index, k, nullptr);
                return;
              }
              const FaceLayer layer = changed_pixels(f.image, *swapped, share);
              frames.add_layer(f.index, k, layer.box.area() > 0 ? &layer : nullptr);
            });
        return [stream = stream.get()](const CapturedFrame& f) { stream->push(f); };
      });
  for (const FoundFace& found : summary.target.faces) {
    const auto it = streams.find(found.index);
    if (it == streams.end()) {  // left as it is
      summary.swapped.push_back(0);
      continue;
    }
    FaceSwapStream& stream = *it->second;
    stream.finish();
    add_stream_timings(summary.timings, stream);
    summary.swapped.push_back(stream.swapped());
  }
  frames.finish();
  if (frames.written() == 0) throw Error("no frames could be read from " + target);
  // A copy of the input marked as a swap would be neither: nothing is written.
  if (summary.timings.swapped == 0 && streams.empty() && !summary.target.faces.empty())
    throw Error("every face of " + target + " is left as it is (--leave-faces): nothing to swap");
  if (summary.timings.swapped == 0) throw Error(no_face_error(target, summary.target.damage, "nothing to swap"));
  writer.finish();
  summary.timings.job_cpu = cpu.taken(writer.encoder_cpu_ms());
  mark.parameters["faces"] = std::to_string(streams.size());
  write_synthetic_sidecar(output, mark);
  if (matte) matte->finish();
  return summary;
}

}  // namespace facecap
