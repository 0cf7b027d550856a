#include "facecap/pipeline/transform_job.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/compose/face_reshading.hpp"
#include "facecap/compose/mouth_warp.hpp"
#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/io/edit_output.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/pipeline/shot_animations.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A tracked frame waiting for its transformed weights (k frames of delay).
struct Pending {
  CapturedFrame frame;
  Positions coarse;  // camera-space face region, source expression
  ShCoeffs lighting;
};

}  // namespace

TransformSummary run_transform(const FaceModel& model, const std::string& input, const fs::path& output,
                               const TransformJobOptions& options) {
  auto source = open_input(input, options.capture.start_seconds);
  const InputInfo info = source->info();
  ensure_writable_file(fs::absolute(output));  // a folder, say, is named as such
  check_edit_output(output, info.kind);        // a video, or an image for a photo
  const ExpressionMapper mapper(options.models_dir);
  for (const ScheduleKey& k : options.transform.schedule.keys()) {
    if (k.target != Emotion::kNeutral) mapper.pair(k.target);  // fail before any work on a missing model
  }
  if (options.transform.from != Emotion::kNeutral) mapper.pair(options.transform.from);

  // An output that would replace the input, or an unwritable glTF path,
  // fails before the work, as an unwritable video path does.
  ensure_not_an_input(output, {input});
  if (!options.gltf.empty()) {
    ensure_writable_file(fs::absolute(options.gltf));
    ensure_not_an_input(options.gltf, {input});
  }
  if (!options.plot.empty()) ensure_not_an_input(options.plot, {input});

  SyntheticMark mark;
  mark.kind = "expression-transform";
  mark.description = "The facial expression was changed by facecap (" + options.description +
                     "); the lips follow the original speech.";
  mark.sources = {input};
  mark.parameters = {{"description", options.description},
                     {"method", options.transform.method == MappingMethod::kLinear ? "linear" : "cyclegan"},
                     {"start_seconds", std::to_string(start_time(info))}};
  VideoWriterOptions vo = output_like(info, options.capture.max_frames);
  vo.metadata = synthetic_metadata(mark);
  EditOutput writer(output, info.kind, vo);

  ExpressionTransformer transformer(mapper, lip_basis(model), options.transform);
  const TriangleMesh face = model.region_mesh(regions::kFace);
  const std::vector<Triangle> skin = masked_triangles(face.triangles, face_skin_mask());
  std::vector<int> inner_lips;
  for (int i = 60; i < 68; ++i) inner_lips.push_back(model.landmarks.vertices[i]);

  TransformSummary summary;
  std::map<int, Pending> pending;
  std::optional<ShotAnimations> animations;  // --gltf, one file per shot
  auto emit = [&](const std::vector<TransformedFrame>& done) {
    for (const TransformedFrame& t : done) {
      auto it = pending.find(t.index);
      if (it == pending.end()) continue;
      const Pending& p = it->second;
      cv::Mat out = p.frame.image;
      if (t.valid) {
        const auto t0 = std::chrono::steady_clock::now();
        const PinholeCamera cam = PinholeCamera::centered(p.frame.fit.focal, info.width, info.height);
        const Positions changed = to_camera(
            model.evaluate(p.frame.identity.identity.cast<float>(), t.weights, regions::kFace), p.frame.fit.pose);
        FaceLayer layer = reshade_face(p.frame.image, p.coarse, changed, skin, p.lighting, cam);
        warp_mouth(p.frame.image, project_vertices(p.coarse, inner_lips, cam),
                   project_vertices(changed, inner_lips, cam), layer);
        out = p.frame.image.clone();
        composite_layer(out, layer);
        summary.timings.render_ms += ms_since(t0);
      }
      writer.write(out, output_time(info, p.frame.index, p.frame.time));
      if (t.valid && animations)
        append_animation_key(animations->keys(p.frame.shot, p.frame.identity), has_timeline(info), t.index, t.time,
                             p.frame.fit.pose, t.weights, key_gaze(p.frame.fit.gaze));
      summary.frames.push_back(t);
      pending.erase(it);
    }
  };

  // The lighting (only: the source frame carries the fine detail), the
  // mapping and the re-render run on the refinement stage's thread,
  // concurrently with the next frames' capture (§4.4.1's pipelining); frames
  // reach it and leave it in order, so the results are those of one thread.
  RefineStage stage(model, lighting_only_refinement(), [&](const RefinedFrame& r) {
    const CapturedFrame& f = r.frame;
    Pending p;
    p.frame = f;
    std::optional<Eigen::VectorXf> weights;
    if (r.refinement) {
      p.coarse = r.coarse;
      p.lighting = r.refinement->lighting;
      weights = f.fit.expression;
    }
    pending.emplace(f.index, std::move(p));
    const auto t0 = std::chrono::steady_clock::now();
    const auto done = transformer.push(f.index, f.time, weights);
    summary.timings.mapping_ms += ms_since(t0);
    emit(done);
  });
  // At a cut the smoothing window stops (it does not reach across), and the
  // shot's glTF is written while the refiner still holds its albedo.
  stage.on_shot_end([&] {
    emit(transformer.finish());
    if (animations) animations->end_shot();
  });
  if (!options.gltf.empty()) {
    animations.emplace(
        options.gltf,
        [&](const ShotOutput& out, const ShotKeys& shot) {
          const IdentityEstimate& id = shot.identity;
          GltfAnimatedMesh glb = face_animation(model, id.identity, shot.keys, {id.focal, info.width, info.height});
          glb.primitives.front().base_colour_png = face_albedo_png(model, stage.refiner());  // the face part
          glb.animation_name =
              shot_animation_name(fs::path(input).stem().string() + " (" + options.description + ")", shot.shot);
          glb.asset_extras.merge(synthetic_metadata(mark));
          write_glb(out.write_to, glb);
          write_synthetic_sidecar(out.file, mark, out.sidecar_to);
        },
        std::vector<std::string>{input});
  }
  CaptureOptions capture = options.capture;
  capture.keep_images = true;
  summary.capture = run_capture(model, *source, capture, [&](const CapturedFrame& f) { stage.push(f); });
  stage.finish();
  summary.timings.lighting_ms = stage.refine_ms();
  emit(transformer.finish());
  summary.timings.frames = static_cast<int>(summary.frames.size());
  if (summary.frames.empty()) throw Error("no frames could be read from " + input);
  // A copy of the input marked as transformed would be neither: nothing is written.
  if (std::none_of(summary.frames.begin(), summary.frames.end(), [](const TransformedFrame& t) { return t.valid; }))
    throw Error("no face found in any frame of " + input + ": nothing to transform");
  writer.finish();
  write_synthetic_sidecar(output, mark);
  if (animations) summary.animation_files = animations->finish();
  if (!options.plot.empty()) write_weight_plot(options.plot, summary.frames, model.expression_names);
  return summary;
}

void write_weight_plot(const fs::path& path, const std::vector<TransformedFrame>& frames,
                       const std::vector<std::string>& names, int curves) {
  // The weights the transformation changed most (mean |result - tracked|).
  const int n = static_cast<int>(names.size());
  std::vector<std::pair<double, int>> change;
  for (int k = 0; k < n; ++k) {
    double c = 0;
    for (const auto& f : frames)
      if (f.valid) c += std::abs(f.weights[k] - f.tracked[k]);
    change.emplace_back(-c, k);
  }
  std::sort(change.begin(), change.end());
  const int panel_w = 900, panel_h = 180, margin = 40;
  const int count = std::min(curves, n);
  cv::Mat img(count * panel_h, panel_w, CV_8UC3, cv::Scalar(255, 255, 255));
  const struct {
    const char* label;
    cv::Scalar colour;
  } series[] = {{"tracking", cv::Scalar(0, 160, 0)},
                {"cg (mapped)", cv::Scalar(200, 80, 0)},
                {"lip+cg", cv::Scalar(200, 200, 0)},
                {"lip+smooth (result)", cv::Scalar(0, 0, 220)}};
  const int total = static_cast<int>(frames.size());
  for (int c = 0; c < count; ++c) {
    const int k = change[c].second;
    const int top = c * panel_h;
    cv::rectangle(img, cv::Rect(margin, top + 20, panel_w - 2 * margin, panel_h - 40), cv::Scalar(220, 220, 220));
    cv::putText(img, names[k], cv::Point(margin, top + 15), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
    for (int s = 0; s < 4; ++s) {
      std::vector<cv::Point> pts;
      for (int i = 0; i < total; ++i) {
        const TransformedFrame& f = frames[i];
        if (!f.valid) continue;
        const float v = s == 0 ? f.tracked[k] : s == 1 ? f.mapped[k] : s == 2 ? f.lip_only[k] : f.weights[k];
        const int x = margin + (panel_w - 2 * margin) * i / std::max(1, total - 1);
        const int y = top + panel_h - 20 - int((panel_h - 40) * std::clamp(v, 0.0f, 1.0f));
        pts.emplace_back(x, y);
      }
      cv::polylines(img, pts, false, series[s].colour, s == 3 ? 2 : 1, cv::LINE_AA);
      if (c == 0) {
        cv::putText(img, series[s].label, cv::Point(panel_w - 230, top + 35 + 14 * s), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                    series[s].colour, 1, cv::LINE_AA);
      }
    }
  }
  AtomicFile file(path);
  if (!cv::imwrite(file.temp_path().string(), img)) throw Error("cannot write " + path.string());
  file.commit();
}

}  // namespace facecap
