#include "facecap/pipeline/transform_job.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/core/atomic_file.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/io/edit_output.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/matte_output.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/face_transform_stream.hpp"
#include "facecap/pipeline/layered_frames.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/shot_animations.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// The checks before any work: a missing expression model, an output that
// is not writable or would replace the input (a folder, say, is named as
// such), an unwritable glTF or plot path.
void check_transform_job(const std::string& input, const InputInfo& info, const fs::path& output,
                         const TransformJobOptions& options, const ExpressionMapper& mapper) {
  ensure_writable_file(fs::absolute(output));
  check_edit_output(output, info.kind);  // a video, or an image for a photo
  auto check_schedule = [&mapper](const ExpressionSchedule& schedule) {
    for (const ScheduleKey& k : schedule.keys()) {
      if (k.target != Emotion::kNeutral) mapper.pair(k.target);
    }
  };
  check_schedule(options.transform.schedule);
  for (const auto& [face, expression] : options.face_expressions) {
    if (face < 0) throw Error("a face's index must be 0 or more, not " + std::to_string(face));
    check_schedule(expression.schedule);
  }
  if (options.transform.from != Emotion::kNeutral) mapper.pair(options.transform.from);
  ensure_not_an_input(output, {input});
  if (!options.gltf.empty()) {
    ensure_writable_file(fs::absolute(options.gltf));
    ensure_not_an_input(options.gltf, {input});
  }
  if (!options.plot.empty()) ensure_not_an_input(options.plot, {input});
  if (!options.matte.empty()) check_matte_output(options.matte, output, info.kind, {input});
}

SyntheticMark transform_mark(const std::string& input, const InputInfo& info, const TransformJobOptions& options) {
  SyntheticMark mark;
  mark.kind = "expression-transform";
  std::string what = options.description;
  for (const auto& [face, expression] : options.face_expressions)
    what += "; face " + std::to_string(face) + ": " + expression.description;
  mark.description =
      "The facial expression was changed by facecap (" + what + "); the lips follow the original speech.";
  mark.sources = {input};
  mark.parameters = {{"description", options.description},
                     {"method", !options.transform.shape_targets.empty()             ? "facs-units"
                                : options.transform.method == MappingMethod::kLinear ? "linear"
                                                                                     : "cyclegan"},
                     {"lip_weight", csv_number(options.transform.lips.alpha)},
                     {"start_seconds", std::to_string(start_time(info))}};
  for (const auto& [face, expression] : options.face_expressions)
    mark.parameters["face_" + std::to_string(face)] = expression.description;
  return mark;
}

VideoWriterOptions marked_output(const InputInfo& info, const TransformJobOptions& options, const SyntheticMark& mark) {
  VideoWriterOptions vo = output_like(info, options.capture.max_frames, options.encoding);
  vo.metadata = synthetic_metadata(mark);
  return vo;
}

}  // namespace

TransformSummary run_transform(const FaceModel& model, const std::string& input, const fs::path& output,
                               const TransformJobOptions& options) {
  if (!options.face_expressions.empty())
    throw Error("an expression per face (--face-to, --face-schedule) needs --all-faces");
  auto source = open_input(input, options.capture.start_seconds);
  const InputInfo info = source->info();
  const ExpressionMapper mapper(options.models_dir);
  check_transform_job(input, info, output, options, mapper);
  const SyntheticMark mark = transform_mark(input, info, options);
  EditOutput writer(output, info.kind, marked_output(info, options, mark));
  std::optional<MatteOutput> matte;
  if (!options.matte.empty()) matte.emplace(options.matte, output, info.kind, marked_output(info, options, mark), mark);

  TransformSummary summary;
  const JobCpuClock cpu;
  std::optional<ShotAnimations> animations;  // --gltf, one file per shot
  FaceTransformStream stream(
      model, mapper, options.transform, options.covers, info.width, info.height, [&](const TransformedFaceFrame& t) {
        cv::Mat out = t.frame.image;
        if (t.layer) {
          const auto t0 = std::chrono::steady_clock::now();
          out = t.frame.image.clone();
          composite_layer(out, *t.layer);
          summary.timings.render_ms += ms_since(t0);
        }
        const double time = output_time(info, t.frame.index, t.frame.time);
        writer.write(out, time);
        if (matte)
          matte->write(t.layer ? layer_blend_mask(*t.layer) : cv::Mat(), t.layer ? t.layer->box : cv::Rect(),
                       t.frame.image.size(), time);
        if (options.on_frame) options.on_frame(t.frame.index, out);
        if (t.weights.valid && animations)
          append_animation_key(animations->keys(t.frame.shot, t.frame.identity), has_timeline(info), t.weights.index,
                               t.weights.time, t.frame.fit.pose, t.weights.weights, key_gaze(t.frame.fit.gaze));
        summary.frames.push_back(t.weights);
      });
  // At a cut the shot's glTF is written while the refiner still holds its albedo.
  stream.on_shot_end([&] {
    if (animations) animations->end_shot();
  });
  if (!options.gltf.empty()) {
    animations.emplace(
        options.gltf,
        [&](const ShotOutput& out, const ShotKeys& shot) {
          const IdentityEstimate& id = shot.identity;
          GltfAnimatedMesh glb = face_animation(model, id.identity, shot.keys, {id.focal, info.width, info.height});
          glb.primitives.front().base_colour_png = face_albedo_png(model, stream.refiner());  // the face part
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
  summary.capture = run_capture(model, *source, capture, [&](const CapturedFrame& f) { stream.push(f); });
  stream.finish();
  summary.timings.add_stream(stream.timings());
  summary.timings.frames = static_cast<int>(summary.frames.size());
  if (summary.frames.empty()) throw Error("no frames could be read from " + input);
  // A copy of the input marked as transformed would be neither: nothing is written.
  if (std::none_of(summary.frames.begin(), summary.frames.end(), [](const TransformedFrame& f) { return f.valid; }))
    throw Error(no_face_error(input, summary.capture.damage, "nothing to transform"));
  writer.finish();
  summary.timings.job_cpu = cpu.taken(writer.encoder_cpu_ms());
  write_synthetic_sidecar(output, mark);
  if (matte) matte->finish();
  if (animations) summary.animation_files = animations->finish();
  if (!options.plot.empty()) write_weight_plot(options.plot, summary.frames, model.expression_names);
  return summary;
}

AllFacesTransformSummary run_transform_all_faces(const FaceModel& model, const std::string& input,
                                                 const fs::path& output, const TransformJobOptions& options,
                                                 const AllFacesOptions& all) {
  if (!options.gltf.empty() || !options.plot.empty())
    throw Error("--gltf and --plot are for one face: they cannot be used with --all-faces");
  for (const auto& [face, expression] : options.face_expressions) {
    if (all.unedited.contains(face))
      throw Error("face " + std::to_string(face) + " is both left as it is (--leave-faces) and given an expression");
  }
  auto source = open_input(input, options.capture.start_seconds);
  const InputInfo info = source->info();
  const ExpressionMapper mapper(options.models_dir);
  check_transform_job(input, info, output, options, mapper);
  SyntheticMark mark = transform_mark(input, info, options);
  mark.parameters["faces"] = "all";
  EditOutput writer(output, info.kind, marked_output(info, options, mark));

  AllFacesTransformSummary summary;
  const JobCpuClock cpu;
  LayeredFrames frames(
      [&](const cv::Mat& image, int index, double time) {
        writer.write(image, output_time(info, index, time));
        if (options.on_frame) options.on_frame(index, image);
      },
      [](cv::Mat& frame, const FaceLayer& layer) { composite_layer(frame, layer); });
  std::optional<MatteOutput> matte;
  if (!options.matte.empty()) {
    matte.emplace(options.matte, output, info.kind, marked_output(info, options, mark), mark);
    frames.on_matte([&](const cv::Mat& image, int index, double time) {
      matte->write(image, cv::Rect({0, 0}, image.size()), image.size(), output_time(info, index, time));
    });
  }
  // One stream per face edited (by FoundFace::index), each on its thread;
  // the frames go to the output once every face in them is re-rendered.
  // Declared after `frames`, so that their threads end before it goes.
  struct Face {
    std::unique_ptr<FaceTransformStream> stream;
    std::vector<TransformedFrame> frames;
  };
  std::map<int, Face> faces;
  summary.capture =
      capture_all_faces_into(frames, model, *source, options.capture, all, [&](const FoundFace& found) -> FrameSink {
        Face& face = faces[found.index];
        TransformOptions transform = options.transform;
        if (const auto own = options.face_expressions.find(found.index); own != options.face_expressions.end())
          transform.schedule = own->second.schedule;
        face.stream =
            std::make_unique<FaceTransformStream>(model, mapper, transform, options.covers, info.width, info.height,
                                                  [&frames, &face, k = found.index](const TransformedFaceFrame& t) {
                                                    face.frames.push_back(t.weights);
                                                    frames.add_layer(t.frame.index, k, t.layer);
                                                  });
        return [&face](const CapturedFrame& f) { face.stream->push(f); };
      });
  for (const FoundFace& found : summary.capture.faces) {
    const auto it = faces.find(found.index);
    if (it == faces.end()) {  // left as it is
      summary.frames.emplace_back();
      continue;
    }
    Face& face = it->second;
    face.stream->finish();
    summary.timings.add_stream(face.stream->timings());
    summary.frames.push_back(std::move(face.frames));
  }
  frames.finish();
  summary.timings.render_ms += frames.composite_ms();
  summary.timings.frames = frames.written();
  if (frames.written() == 0) throw Error("no frames could be read from " + input);
  const bool any = std::any_of(summary.frames.begin(), summary.frames.end(), [](const auto& face) {
    return std::any_of(face.begin(), face.end(), [](const TransformedFrame& f) { return f.valid; });
  });
  if (!any && faces.empty() && !summary.capture.faces.empty())
    throw Error("every face of " + input + " is left as it is (--leave-faces): nothing to transform");
  if (!any) throw Error(no_face_error(input, summary.capture.damage, "nothing to transform"));
  writer.finish();
  summary.timings.job_cpu = cpu.taken(writer.encoder_cpu_ms());
  mark.parameters["faces"] = std::to_string(faces.size());
  write_synthetic_sidecar(output, mark);
  if (matte) matte->finish();
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
  write_image(path, img);
}

}  // namespace facecap
