#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/expr/action_units.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/transform_job.hpp"

namespace facecap::cli {

namespace {

void report_transform(const TransformTimings& t, const std::string& output) {
  const double n = std::max(1, t.frames);
  std::fprintf(stderr,
               "per frame: mapping+smoothing+QP %.2f ms, lighting %.2f ms, re-render+composite %.2f ms, covers %.2f ms "
               "(+ %.2f ms beside; their optical flow on %d of %d frames)\nwrote %s and %s.json (synthetic-media "
               "marks)\n",
               t.mapping_ms / n, t.lighting_ms / n, t.render_ms / n, t.covers_ms / n, t.cover_preparation_ms / n,
               t.cover_flow_frames, t.frames, output.c_str(), output.c_str());
}

}  // namespace

void register_transform(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("transform",
                                 "Change a speaking face's expression (anger, disgust, fear, happiness, sadness, "
                                 "surprise, neutral, or FACS action units) with the lips kept in sync; writes a video "
                                 "marked as synthetic");
  struct Args {
    std::string input, output, to = "happiness", from = "neutral", method = "cyclegan", schedule, plot, gltf, models,
                               units;
    double intensity = 1.0;
    int window = 1;
    bool all_faces = false;
    std::vector<std::string> face_to, face_schedule;
    TransformJobOptions options;
    AllFacesOptions all;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUT", a->input, "Video file, image folder or cam:N")->required();
  cmd->add_option("-o,--output", a->output,
                  "Output video (.mp4, .m4v, .mov or .mkv), or for a photo also an image (.png, .jpg, .jpeg) marked "
                  "as synthetic in its metadata; OUT.json is its synthetic-media sidecar")
      ->required();
  CLI::Option* to = cmd->add_option("--to", a->to, std::string("Target expression: ") + emotion_choices())
                        ->check(emotion_value())
                        ->capture_default_str();
  CLI::Option* from = cmd->add_option("--from", a->from,
                                      "Expression the input shows, to change from (a --to the same is refused: "
                                      "nothing would change; --from happiness --to neutral takes a smile away)")
                          ->check(emotion_value())
                          ->capture_default_str();
  cmd->add_option("--intensity", a->intensity, "Share of the change, 0..1")
      ->check(number_between(0, 1))
      ->capture_default_str();
  CLI::Option* schedule = cmd->add_option("--schedule", a->schedule,
                                          "File of 'seconds target intensity' keys with transitions between them");
  CLI::Option* method = cmd->add_option("--method", a->method, "cyclegan, or the linear baseline of eq. 5.5")
                            ->check(CLI::IsMember({"cyclegan", "linear"}))
                            ->capture_default_str();
  CLI::Option* units = add_action_units_option(
      *cmd, a->units,
      "Instead of an emotion, set FACS action units (as track --action-units reads them) to the intensities given, "
      "0-5, in every frame: AU12=3,AU6=2 adds a smile, AU4=0 smooths a frown; the lips stay in sync as with --to, "
      "which may hold back a unit that moves them (AU12, AU15, AU26 ...). With --intensity");
  units->excludes(to)->excludes(from)->excludes(schedule)->excludes(method);
  cmd->add_option("--window", a->window, "Smoothing window half-width k (2k + 1 frames)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  CLI::Option* plot =
      cmd->add_option("--plot", a->plot, "Write a PNG of weight curves (tracked, mapped, lip-corrected, smoothed)");
  CLI::Option* gltf =
      cmd->add_option("--gltf", a->gltf,
                      "Also write the transformed performance as an animated glTF (.glb, as track --gltf; marked as "
                      "synthetic, with a sidecar .json). An input that cuts gets one per shot: OUT_shot<N>.glb after "
                      "the first");
  add_matte_option(*cmd, a->options.matte, "re-rendered face");
  add_transform_cover_flags(*cmd, a->options.covers);
  add_lip_weight_option(*cmd, a->options.transform.lips);
  add_encoding_options(*cmd, a->options.encoding, "the output video (a --matte is lossless)");
  cmd->add_option("--models", a->models, "Expression models folder (default: models/expressions)");
  add_frame_range_options(*cmd, a->options.capture);
  CLI::Option* face = add_fit_options(*cmd, a->options.capture).face;
  CLI::Option* identity = add_identity_option(*cmd, a->options.capture.fit.known_identity);
  CLI::Option* all_faces = add_all_faces_options(
      *cmd, a->all_faces, a->all,
      "Transform every face the input shows into the one output, each from the frame it is first found in (a face "
      "entering later is found within --search-every frames), each with its own identity, lighting and smoothing");
  all_faces->excludes(face)->excludes(identity)->excludes(plot)->excludes(gltf);  // one face's
  add_leave_faces_option(*cmd, all_faces, a->all);
  cmd->add_option("--face-to", a->face_to,
                  "--all-faces: give face K an expression of its own, K=EMOTION (say 1=sadness; with --intensity), "
                  "instead of --to; repeat for more faces")
      ->type_name("K=EMOTION")
      ->needs(all_faces)
      ->excludes(units)
      ->check(face_value_check([](const std::string& emotion) { emotion_argument("the expression", emotion); }));
  cmd->add_option("--face-schedule", a->face_schedule,
                  "--all-faces: give face K a schedule of its own, K=FILE (as --schedule); repeat for more faces")
      ->type_name("K=FILE")
      ->needs(all_faces)
      ->excludes(units)
      ->check(face_value_check());
  cmd->callback([a, &global] {
    const Emotion to = emotion_argument("--to", a->to), from = emotion_argument("--from", a->from);
    // An edit from an expression to itself changes nothing: a smiling clip
    // asked `--to neutral` (from the default neutral) came out as it went in.
    if (to == from && a->units.empty() && a->schedule.empty() && a->face_to.empty() && a->face_schedule.empty())
      throw CLI::ValidationError(
          "--to " + std::string(to_string(to)) + " is the input's expression already (--from " + to_string(from) +
          "), so nothing would change; to take an emotion away, name it: --from happiness --to neutral");
    TransformJobOptions& o = a->options;
    o.transform.from = from;
    o.transform.schedule =
        a->schedule.empty() ? ExpressionSchedule::constant(to, a->intensity) : ExpressionSchedule::read(a->schedule);
    o.transform.method = a->method == "linear" ? MappingMethod::kLinear : MappingMethod::kCycleGan;
    o.transform.window = a->window;
    o.plot = a->plot;
    o.gltf = a->gltf;
    if (!a->models.empty()) o.models_dir = a->models;
    o.description =
        a->schedule.empty() ? std::string(to_string(from)) + " to " + to_string(to) : "schedule " + a->schedule;
    // Faces with an expression of their own.
    auto add_face = [&o](const std::pair<int, std::string>& face, const ExpressionSchedule& schedule,
                         const std::string& description) {
      if (!o.face_expressions.emplace(face.first, TransformJobOptions::FaceExpression{schedule, description}).second)
        throw CLI::ValidationError("face " + std::to_string(face.first) +
                                   " is given two expressions (--face-to, --face-schedule)");
    };
    for (const std::string& text : a->face_to) {
      const auto face = parse_face_value(text);
      const Emotion target = *parse_emotion(face.second);  // checked as parsed
      add_face(face, ExpressionSchedule::constant(target, a->intensity),
               std::string(to_string(from)) + " to " + to_string(target));
    }
    for (const std::string& text : a->face_schedule) {
      const auto face = parse_face_value(text);
      add_face(face, ExpressionSchedule::read(face.second), "schedule " + face.second);
    }
    o.capture.quiet = global.quiet;
    const FaceModel model = load_model(global);
    if (!a->units.empty()) {  // a FACS edit instead of the emotion
      const std::vector<ActionUnitTarget> targets = parse_action_unit_targets(a->units);
      o.transform.shape_targets = ActionUnitReader(model.expression_names).shape_weights(targets);
      o.description = "FACS units " + describe(targets);
    }
    if (a->all_faces) {
      const AllFacesTransformSummary s = run_transform_all_faces(model, a->input, a->output, o, a->all);
      report_edited_faces(
          s.capture, a->all, "transformed",
          [&s](int k) {
            return int(std::count_if(s.frames[k].begin(), s.frames[k].end(),
                                     [](const TransformedFrame& f) { return f.valid; }));
          },
          [&o](int k) {
            const auto own = o.face_expressions.find(k);
            return own != o.face_expressions.end() ? own->second.description : std::string();
          });
      report_transform(s.timings, a->output);
      report_uncaptured_faces(s.capture, "left as they are");
      std::vector<int> named;
      for (const auto& [face, expression] : o.face_expressions) named.push_back(face);
      report_unfound_faces(named, s.capture, "--face-to, --face-schedule");
      return;
    }
    const TransformSummary s = run_transform(model, a->input, a->output, o);
    std::fprintf(stderr, "frames %d, lost %d\n", s.capture.frames, s.capture.lost);
    report_transform(s.timings, a->output);
    if (const std::string note = unreadable_frames_note(s.capture, a->input); !note.empty())
      std::fprintf(stderr, "facecap: %s (black in the output)\n", note.c_str());
    report_damaged_input(s.capture.damage, a->input);
    for (const std::filesystem::path& file : s.animation_files)
      std::fprintf(stderr, "wrote %s and %s.json\n", file.c_str(), file.c_str());
    if (!o.matte.empty()) std::fprintf(stderr, "wrote %s and %s.json (the matte)\n", o.matte.c_str(), o.matte.c_str());
  });
}

}  // namespace facecap::cli
