#include "facecap/pipeline/swap_job.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/io/edit_output.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/pipeline/shot_animations.hpp"

namespace facecap {

namespace fs = std::filesystem;

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
  CaptureOptions capture;
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
  if (const std::string note = unreadable_frames_note(summary, "the source " + source); !note.empty() && !quiet) {
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
  // The photo is all the frames there are: it fixes the albedo at once, with
  // the fixing frame's lighting/albedo rounds (4) rather than an early
  // frame's (2). Self-swap (`eval swap --self`) mean 6.100 -> 6.070
  // (address_720p_a), 9.502 -> 9.474 (_b).
  RefineOptions photo_refine = lighting_only_refinement();
  photo_refine.albedo.frames = 1;
  Refiner refiner = make_face_refiner(model, photo_refine);
  s.lighting = refiner.refine(r.photo, s.camera_points, s.camera).lighting;
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
  if (!texture.empty() && !cv::imencode(".png", texture, glb.primitives.front().base_colour_png))
    throw Error("cannot encode the swapped face's texture");
  glb.asset_extras["model"] =
      "ICT Face Model Light (ICT-FaceKit, MIT): face region, mouth and eyes, the source's identity";
  glb.asset_extras.merge(synthetic_metadata(mark));
  return glb;
}

}  // namespace

SwapSummary run_swap(const FaceModel& model, const std::string& source_photo, const std::string& target,
                     const fs::path& output, const SwapJobOptions& options) {
  // Unwritable outputs fail before the work (the source's fit included).
  ensure_writable_file(fs::absolute(output));
  ensure_not_an_input(output, {source_photo, target});
  if (!options.gltf.empty()) {
    ensure_writable_file(fs::absolute(options.gltf));
    ensure_not_an_input(options.gltf, {source_photo, target});
  }
  auto input = open_input(target, options.capture.start_seconds);  // a bad target fails before the source's fit
  check_edit_output(output, input->info().kind);                   // a video, or an image for a photo target
  SwapSummary summary;
  auto t0 = std::chrono::steady_clock::now();
  summary.source =
      reconstruct_source(model, source_photo, options.capture.quiet, options.source_frames, options.source_face);
  summary.timings.source_ms = ms_since(t0);
  const InputInfo info = input->info();

  SyntheticMark mark;
  mark.kind = "face-swap";
  mark.description = std::string("The face in this ") + (info.kind == InputKind::kImage ? "image" : "video") +
                     " was replaced by facecap with the face from " + fs::path(source_photo).filename().string() + ".";
  mark.sources = {source_photo, target};
  mark.parameters = {{"appearance_frames", std::to_string(options.swap.appearance_frames)},
                     {"warp_background", options.swap.warp_background ? "true" : "false"},
                     {"match_target_size", options.swap.match_target_size ? "true" : "false"},
                     {"mirror_source", options.swap.mirror_source ? "true" : "false"},
                     {"follow_light_colour", options.swap.follow_light_colour ? "true" : "false"},
                     {"residual_shading_mm", std::to_string(options.swap.residual_shading_mm)},
                     {"expression_ratio", options.swap.expression_ratio ? "true" : "false"},
                     {"photo_detail_gain", std::to_string(options.swap.photo_detail_gain)},
                     {"source_frames_used", std::to_string(summary.source.frames_used)},
                     {"target_start_seconds", std::to_string(start_time(info))}};
  VideoWriterOptions vo = output_like(info, options.capture.max_frames);
  vo.metadata = synthetic_metadata(mark);
  EditOutput writer(output, info.kind, vo);

  FaceSwapper swapper(model, summary.source.photo, summary.source.face, options.swap);
  // The target's albedo from its first 4 frames in a row (not every 3rd):
  // the appearance waits for it (TargetFrame::lighting_final), and the
  // lighting of the frames before it is on another scale. Self-swap
  // (`eval swap --self`) median / mean on address_720p_a / _b: 4.325 / 6.210,
  // 6.325 / 9.528 with neither; 4.325 / 6.160, 6.325 / 9.514 waiting for the
  // albedo of every 3rd frame; 4.325 / 6.100, 6.325 / 9.502 with both.
  RefineOptions refine = lighting_only_refinement();
  refine.albedo.interval = 1;
  // With wrinkles the target is refined as `track --refine` does, on a
  // two-level hierarchy (the coarse mesh and one 4-8 level, about 4x the
  // vertices), whose finest level carries the coating transfer.
  if (options.swap.wrinkles) {
    refine.displacements = true;
    refine.hierarchy.levels = 2;
  }
  // --gltf: one file per shot, each with the swapper's placement and
  // texture for that shot and the shot's focal length.
  std::optional<ShotAnimations> animations;
  if (!options.gltf.empty()) {
    animations.emplace(
        options.gltf,
        [&](const ShotOutput& out, const ShotKeys& shot) {
          GltfAnimatedMesh glb = swapped_animation(model, swapper, summary.source.face, shot.keys,
                                                   {shot.identity.focal, info.width, info.height}, mark);
          glb.animation_name = shot_animation_name(
              fs::path(target).stem().string() + " (face from " + fs::path(source_photo).filename().string() + ")",
              shot.shot);
          write_glb(out.write_to, glb);
          write_synthetic_sidecar(out.file, mark, out.sidecar_to);
        },
        std::vector<std::string>{source_photo, target});
  }
  // The target's lighting, the swap and the output run on the refinement
  // stage's thread, concurrently with the next frames' capture (§4.4.1's
  // pipelining); frames reach it and leave it in order, so the results are
  // those of one thread.
  RefineStage stage(model, refine, [&](const RefinedFrame& r) {
    const CapturedFrame& f = r.frame;
    if (r.starts_shot) {
      // A shot cut: what the swapper learnt of the target's first frames
      // (appearance, light colour, expression reference) is of the last shot.
      if (animations) animations->end_shot();
      swapper = FaceSwapper(model, summary.source.photo, summary.source.face, options.swap);
    }
    SwappedFrame result;
    if (!r.refinement) {
      result.image = f.image;
    } else {
      TargetFrame t;
      t.identity = f.identity.identity.cast<float>();
      t.expression = f.fit.expression;
      t.pose = f.fit.pose;
      t.camera = r.camera;
      t.lighting = r.refinement->lighting;
      t.lighting_final = stage.refiner().albedo_fixed();
      if (options.swap.wrinkles) {
        t.fine = r.refinement->positions;
        t.hierarchy = &stage.refiner().hierarchy();
      }
      result = swapper.swap(f.image, t, &summary.timings.swap);
      ++summary.timings.swapped;
      if (animations)
        append_animation_key(animations->keys(f.shot, f.identity), has_timeline(info), f.index, f.time, t.pose,
                             t.expression, key_gaze(f.fit.gaze));
    }
    writer.write(result.image, output_time(info, f.index, f.time));
    if (options.on_frame) options.on_frame(f, result);
  });
  CaptureOptions capture = options.capture;
  capture.keep_images = true;
  summary.target = run_capture(model, *input, capture, [&](const CapturedFrame& f) { stage.push(f); });
  stage.finish();
  summary.timings.lighting_ms = stage.refine_ms();
  if (summary.target.frames == 0) throw Error("no frames could be read from " + target);
  // A copy of the input marked as a swap would be neither: nothing is written.
  if (summary.timings.swapped == 0) throw Error("no face found in any frame of " + target + ": nothing to swap");
  writer.finish();
  write_synthetic_sidecar(output, mark);
  if (animations) summary.animation_files = animations->finish();
  return summary;
}

}  // namespace facecap
