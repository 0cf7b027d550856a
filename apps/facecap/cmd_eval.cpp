#include <filesystem>

#include "commands.hpp"
#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/pipeline/landmark_eval.hpp"
#include "facecap/pipeline/landmark_folder_eval.hpp"
#include "facecap/pipeline/photo_identity_eval.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/swap_eval.hpp"
#include "facecap/pipeline/synth_landmark_eval.hpp"
#include "facecap/pipeline/track_eval.hpp"
#include "facecap/pipeline/transform_eval.hpp"
#include "facecap/refine/displacement_problem_io.hpp"

namespace facecap::cli {

namespace {

// Option combinations that cannot work are usage errors (exit 2), refused
// before any work as a bad value is.
[[noreturn]] void refuse_face_photo_without_synthetic() {
  throw CLI::ValidationError("--face-photo", "needs --synthetic: it is the skin of the renders");
}

// The per-region NME keys both landmark evaluations print.
nlohmann::json region_json(const RegionNme& r) {
  return {
      {"nme_jaw", r.jaw}, {"nme_brows", r.brows}, {"nme_nose", r.nose}, {"nme_eyes", r.eyes}, {"nme_mouth", r.mouth}};
}

void register_eval_landmarks(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand("landmarks",
                                  "Landmark accuracy as JSON: dlib's 68 points on an annotated image (IMAGE PTS); on "
                                  "a folder of annotated images (FOLDER: each image beside its .pts, as 300-W ships "
                                  "them) dlib's and the fitted model's, with mean, median, failure rate and AUC_0.08; "
                                  "or detection rate and NME on synthetic renders (--synthetic N)");
  struct Args {
    std::string image, pts;
    int synthetic = 0;
    uint64_t seed = 1;
    std::string face_photo;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("IMAGE", a->image, "Image file, or a folder of images each beside its .pts annotation");
  cmd->add_option("PTS", a->pts, "iBUG .pts annotation (1-based coordinates)");
  cmd->add_option("--synthetic", a->synthetic, "Render N synthetic frames instead and score against their truth")
      ->check(whole_number_at_least(1));
  cmd->add_option("--seed", a->seed, "Seed of the synthetic performance")->capture_default_str();
  add_face_photo_option(*cmd, a->face_photo);
  cmd->callback([a, &global] {
    if (a->synthetic > 0) {
      const FaceModel model = load_model(global);
      SynthOptions o;
      o.frames = a->synthetic;
      o.seed = a->seed;
      use_face_photo(model, a->face_photo, o);
      const SynthLandmarkEval r = evaluate_synthetic_landmarks(model, o, global.quiet);
      nlohmann::json j = {
          {"frames", r.frames},         {"detected", r.detected}, {"detection_rate", r.detection_rate},
          {"nme_median", r.nme_median}, {"nme_mean", r.nme_mean}, {"nme_inner_median", r.nme_inner_median}};
      j.update(region_json(r.regions));
      print_json(j);
      return;
    }
    if (!a->face_photo.empty()) refuse_face_photo_without_synthetic();
    if (!a->image.empty() && a->pts.empty() && std::filesystem::is_directory(a->image)) {
      const FaceModel model = load_model(global);
      const LandmarkFolderEval r = evaluate_landmark_folder(model, a->image, global.quiet);
      const auto scores = [](const LandmarkScores& s) {
        return nlohmann::json{{"images", s.images},
                              {"scored", s.scored},
                              {"nme_mean", s.nme_mean},
                              {"nme_median", s.nme_median},
                              {"failure_rate_0.08", s.failure_rate},
                              {"auc_0.08", s.auc}};
      };
      nlohmann::json per_image = nlohmann::json::array();
      for (const AnnotatedImageScore& i : r.images) {
        nlohmann::json j = {{"image", i.image}, {"faces", i.faces}};
        j["nme"] = i.nme ? nlohmann::json(*i.nme) : nlohmann::json();
        j["fitted_nme"] = i.fitted_nme ? nlohmann::json(*i.fitted_nme) : nlohmann::json();
        if (!i.error.empty()) j["error"] = i.error;
        per_image.push_back(j);
      }
      print_json({{"folder", a->image},
                  {"normaliser", "outer eye corners (300-W)"},
                  {"unannotated_images", r.unannotated},
                  {"dlib", scores(r.dlib)},
                  {"fitted", scores(r.fitted)},
                  {"per_image", per_image}});
      return;
    }
    if (a->image.empty() || a->pts.empty())
      throw CLI::ValidationError("eval landmarks needs IMAGE and PTS, a folder of annotated images, or --synthetic N");
    const LandmarkEvalResult r = evaluate_landmarks(a->image, a->pts);
    nlohmann::json j = {{"image", a->image},
                        {"faces", r.faces},
                        {"nme", r.nme},
                        {"mean_error_px", r.mean_error_px},
                        {"max_error_px", r.max_error_px}};
    j.update(region_json(r.regions));
    print_json(j);
  });
}

void register_eval_track(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand("track",
                                  "Coarse-tracking accuracy as JSON: on a synthetic performance (--synthetic N) "
                                  "against its truth, or on real footage (--video PATH)");
  struct Args {
    int synthetic = 0;
    std::string video;
    std::string landmarks = "truth";
    std::string size = "1280x720";
    bool map_size = false;
    int photos = 0;
    std::string face_photo;
    TrackEvalOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--synthetic", a->synthetic, "Render and fit N synthetic frames")->check(whole_number_at_least(1));
  cmd->add_option("--video", a->video, "Fit real footage");
  cmd->add_option("--seed", a->options.seed, "Seed of the synthetic performance")->capture_default_str();
  cmd->add_option("--landmarks", a->landmarks, "truth (projected truth + noise) or dlib (on the rendered video)")
      ->check(CLI::IsMember({"truth", "dlib"}))
      ->capture_default_str();
  cmd->add_option("--noise", a->options.landmark_noise_px, "Landmark noise sigma in pixels (truth landmarks)")
      ->check(number_between(0, 100))
      ->capture_default_str();
  cmd->add_option("--still-frames", a->options.still_frames, "Still-head frames for the jitter measurement")
      ->check(whole_number_at_least(0))
      ->capture_default_str();
  cmd->add_flag("!--no-gaze", a->options.capture.gaze,
                "Skip the irises, the gaze and its pull on the eyeLook weights (with truth landmarks it renders "
                "every frame)");
  cmd->add_option("--max-frames", a->options.capture.max_frames, "Stop after this many frames of --video")
      ->check(whole_number_at_least(0));
  add_fit_options(*cmd, a->options.capture);
  cmd->add_flag("--true-focal", a->options.true_focal, "Hold the focal length at the synthetic truth (diagnostic)");
  cmd->add_flag("--true-identity", a->options.true_identity,
                "Hold the identity at the synthetic truth (diagnostic): the vertex error is then what the landmarks "
                "give the expressions and the pose alone");
  cmd->add_flag("--map-size", a->map_size,
                "Keep the identity solve's own face size, without the size correction (diagnostic)");
  cmd->add_option("--yaw", a->options.synth.max_yaw_deg, "Synthetic head turns sweep +-this many degrees")
      ->check(number_between(0, 60))
      ->capture_default_str();
  cmd->add_option("--roll", a->options.synth.camera_roll_deg,
                  "The synthetic camera turned about its axis by this many degrees (90: on its side)")
      ->check(number_between(-180, 180))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Synthetic frame size WxH")->check(synthetic_frame_size())->capture_default_str();
  cmd->add_option("--photos", a->photos,
                  "--synthetic: instead, fit every K-th frame alone, as a photo (a swap's source) is, and report "
                  "how far each photo's identity lies from the true face (size removed), for calm and expressive "
                  "faces")
      ->check(whole_number_at_least(1));
  add_face_photo_option(*cmd, a->face_photo);
  cmd->callback([a, &global] {
    if (!a->video.empty()) {
      if (!a->face_photo.empty()) refuse_face_photo_without_synthetic();
      if (a->photos > 0) throw CLI::ValidationError("--photos", "fits synthetic frames: use it with --synthetic N");
      if (a->options.true_focal || a->options.true_identity)
        throw CLI::ValidationError(a->options.true_focal ? "--true-focal" : "--true-identity",
                                   "needs --synthetic: real footage has no truth to hold");
    } else if (a->synthetic <= 0) {
      throw CLI::ValidationError("eval track needs --synthetic N or --video PATH");
    }
    if (a->photos > 0 && a->landmarks != "truth")
      throw CLI::ValidationError("--photos", "fits the true landmarks; drop --landmarks dlib");
    if (a->photos > 0 && a->options.true_identity)
      throw CLI::ValidationError("--true-identity", "cannot go with --photos, which measures the photos' identities");
    const FaceModel model = load_model(global);
    a->options.capture.quiet = global.quiet;
    if (!a->video.empty()) {
      const VideoEvalResult r = evaluate_track_video(model, a->video, a->options.capture);
      const StageTimings& t = r.summary.timings;
      print_json({{"video", a->video},
                  {"frames", r.frames},
                  {"lost_frames", r.lost_frames},
                  {"landmark_nme", r.landmark_nme},
                  {"landmark_nme_mean", r.landmark_nme_mean},
                  {"landmark_nme_p90", r.landmark_nme_p90},
                  {"focal", r.focal},
                  {"gaze_frames", r.gaze_frames},
                  {"identity_frames", r.summary.identity.frames_used},
                  {"fps", t.fps()}});
      return;
    }
    a->options.frames = a->synthetic;
    parse_size(a->size, a->options.synth.width, a->options.synth.height);
    use_face_photo(model, a->face_photo, a->options.synth);
    a->options.landmarks = a->landmarks == "dlib" ? LandmarkSource::kDlib : LandmarkSource::kTruth;
    a->options.capture.fit.unbiased_size = !a->map_size;
    if (a->photos > 0) {
      const PhotoIdentityEvalResult r = evaluate_photo_identity_synthetic(model, a->options, a->photos);
      print_json({{"frames", a->options.frames},
                  {"seed", a->options.seed},
                  {"photos", r.photos},
                  {"shape_error_mm", r.shape_error_mm},
                  {"shape_error_calm_mm", r.shape_error_calm_mm},
                  {"shape_error_expressive_mm", r.shape_error_expressive_mm},
                  {"weights_mae", r.weights_mae},
                  {"expression_mae_expressive", r.expression_mae_expressive}});
      return;
    }
    const TrackEvalResult r = evaluate_track_synthetic(model, a->options);
    print_json({{"frames", r.frames},
                {"seed", a->options.seed},
                {"landmarks", a->landmarks},
                {"true_focal", a->options.true_focal},
                {"true_identity", a->options.true_identity},
                {"lost_frames", r.lost_frames},
                {"vertex_error_mm", r.vertex_error_mm},
                {"vertex_error_similarity_mm", r.vertex_error_similarity_mm},
                {"rotation_error_deg", r.rotation_error_deg},
                {"yaw_gain", r.yaw_gain},
                {"translation_error_cm", r.translation_error_cm},
                {"focal", r.focal},
                {"focal_true", r.focal_true},
                {"focal_error_rel", r.focal_error_rel},
                {"weights_mae", r.weights_mae},
                {"eye_look_mae", r.eye_look_mae},
                {"action_units_mae", r.action_units_mae},
                {"action_units_correlation", r.action_units_correlation},
                {"action_units_moving", r.action_units_moving},
                {"action_units_f1", r.action_units_f1},
                {"jitter_mm", r.jitter_mm},
                {"jitter_camera_mm", r.jitter_camera_mm},
                {"identity_error", r.identity_error},
                {"size_ratio", r.size_ratio},
                {"size_factor", r.size_factor},
                {"identity_modes_determined", r.effective_modes},
                {"identity_shape_rms_mm", r.identity_shape_rms_mm},
                {"identity_shape_rms_fixed_size_mm", r.identity_shape_rms_fixed_size_mm},
                {"shape_sd_mm", r.shape_sd_mm},
                {"shape_sd_fixed_size_mm", r.shape_sd_fixed_size_mm},
                {"fit_ms_per_frame", r.fit_ms_per_frame},
                {"iris_error_px", r.iris_error_px},
                {"iris_bias_xy_px", {r.iris_bias_px.x(), r.iris_bias_px.y()}},
                {"iris_found", r.iris_found},
                {"gaze_error_deg", r.gaze_error_deg},
                {"gaze_bias_yaw_pitch_deg", {r.gaze_bias_deg.x(), r.gaze_bias_deg.y()}},
                {"gaze_frames", r.gaze_frames}});
  });
}

void register_eval_refine(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand("refine",
                                  "Shading-refinement accuracy as JSON: on synthetic renders with wrinkles "
                                  "(--synthetic N) against their truth, or the photometric error on real footage "
                                  "(--video PATH)");
  struct Args {
    int synthetic = 0;
    std::string video;
    std::string size = "1280x720";
    RefineEvalOptions options;
    CaptureOptions capture;
    std::string save_problems;
    std::string face_photo;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--synthetic", a->synthetic, "Render and refine N synthetic frames")->check(whole_number_at_least(1));
  cmd->add_option("--video", a->video, "Track and refine real footage");
  cmd->add_option("--seed", a->options.seed, "Seed of the synthetic performance")->capture_default_str();
  cmd->add_option("--size", a->size, "Synthetic frame size WxH")->check(synthetic_frame_size())->capture_default_str();
  cmd->add_option("--max-frames", a->capture.max_frames, "Stop after this many frames of --video")
      ->check(whole_number_at_least(0));
  cmd->add_option("--albedo-frames", a->options.refine.albedo.frames, "Frames before the albedo is fixed")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  add_device_option(*cmd, a->options.refine.device);
  cmd->add_option("--save-problems", a->save_problems,
                  "--video: also write each frame's displacement problems to DIR (frameNNNN_levelL.fcdp) for "
                  "`facecap bench displacement`");
  cmd->add_flag("--true-shading", a->options.true_shading,
                "--synthetic: solve the displacements with the render's true lighting and albedo (the estimates "
                "are still made and reported), to measure the displacement solve alone");
  add_face_photo_option(*cmd, a->face_photo);
  cmd->callback([a, &global] {
    if (a->video.empty() && a->synthetic <= 0)
      throw CLI::ValidationError("eval refine needs --synthetic N or --video PATH");
    if (!a->video.empty() && a->options.true_shading)
      throw CLI::ValidationError("--true-shading", "needs --synthetic: real footage has no true shading");
    if (!a->video.empty() && !a->face_photo.empty()) refuse_face_photo_without_synthetic();
    if (!a->save_problems.empty()) {
      if (a->video.empty()) throw CLI::ValidationError("--save-problems", "needs --video");
      ensure_writable_dir(a->save_problems);
      a->options.refine.on_displacement_problem = [dir = std::filesystem::path(a->save_problems)](
                                                      int frame, int level, const DisplacementProblem& problem,
                                                      const Eigen::VectorXf& start) {
        char name[64];
        std::snprintf(name, sizeof(name), "frame%04d_level%d.fcdp", frame, level);
        save_displacement_problem(dir / name, problem, start, frame, level);
      };
    }
    const FaceModel model = load_model(global);
    if (!a->video.empty()) {
      a->capture.quiet = global.quiet;
      const RefineVideoResult r = evaluate_refine_video(model, a->video, a->capture, a->options.refine);
      print_json({{"video", a->video},
                  {"frames", r.frames},
                  {"photometric_coarse", r.photometric_coarse},
                  {"photometric_refined", r.photometric_refined},
                  {"photometric_shading_floor", r.photometric_shading_floor},
                  {"reduction", r.photometric_coarse > 0 ? 1.0 - r.photometric_refined / r.photometric_coarse : 0.0},
                  {"refine_ms_per_frame", r.refine_ms_per_frame},
                  {"device", to_string(a->options.refine.device)}});
      return;
    }
    a->options.frames = a->synthetic;
    parse_size(a->size, a->options.width, a->options.height);
    a->options.face_texture = face_photo_texture(model, a->face_photo);
    a->options.quiet = global.quiet;
    const RefineEvalResult r = evaluate_refine_synthetic(model, a->options);
    print_json({{"frames", r.frames},
                {"seed", a->options.seed},
                {"levels", r.levels},
                {"finest_vertices", r.finest_vertices},
                {"lighting_error_rel", r.lighting_error_rel},
                {"lighting_error_terms",
                 std::vector<double>(r.lighting_error_terms.data(), r.lighting_error_terms.data() + 9)},
                {"shading_error_rel", r.shading_error_rel},
                {"albedo_corr", r.albedo_corr},
                {"normal_error_deg", r.normal_error_deg},
                {"normal_error_coarse_deg", r.normal_error_coarse_deg},
                {"detail_pixel_fraction", r.detail_pixel_fraction},
                {"normal_error_detail_deg", r.normal_error_detail_deg},
                {"normal_error_detail_coarse_deg", r.normal_error_detail_coarse_deg},
                {"normal_error_flat_deg", r.normal_error_flat_deg},
                {"normal_error_flat_coarse_deg", r.normal_error_flat_coarse_deg},
                {"normal_error_oracle_deg", r.normal_error_oracle_deg},
                {"normal_error_detail_oracle_deg", r.normal_error_detail_oracle_deg},
                {"true_shading", a->options.true_shading},
                {"vertex_error_mm", r.vertex_error_mm},
                {"vertex_error_coarse_mm", r.vertex_error_coarse_mm},
                {"refine_ms_per_frame", r.refine_ms_per_frame}});
  });
}

void register_eval_transform(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand("transform",
                                  "Expression-transformation measures as JSON on real footage: lip error, rise of the "
                                  "target's defining weights, smoothness against the per-frame mapping, audio");
  struct Args {
    std::string video, to = "happiness", output, method = "cyclegan", units;
    TransformJobOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--video", a->video, "Footage of a speaking face")->required();
  CLI::Option* to = cmd->add_option("--to", a->to, std::string("Target expression: ") + emotion_choices())
                        ->check(emotion_value())
                        ->capture_default_str();
  CLI::Option* method = cmd->add_option("--method", a->method, "cyclegan, or the linear baseline of eq. 5.5")
                            ->check(CLI::IsMember({"cyclegan", "linear"}))
                            ->capture_default_str();
  add_action_units_option(*cmd, a->units,
                          "Instead of an emotion, measure a FACS edit (as transform --units): for each unit the "
                          "intensity asked, the input's, the output's and the output's tracked again (\"units\")")
      ->excludes(to)
      ->excludes(method);
  cmd->add_option("--max-frames", a->options.capture.max_frames, "Stop after this many frames")
      ->check(whole_number_at_least(0));
  add_fit_options(*cmd, a->options.capture);
  add_transform_cover_flags(*cmd, a->options.covers);
  add_lip_weight_option(*cmd, a->options.transform.lips);
  cmd->add_option("-o,--output", a->output, "Keep the transformed video here (default: a temporary file)");
  cmd->add_option("--models", a->options.models_dir, "Expression models folder");
  cmd->callback([a, &global] {
    const Emotion to = emotion_argument("--to", a->to);
    const FaceModel model = load_model(global);
    a->options.capture.quiet = global.quiet;
    a->options.transform.method = a->method == "linear" ? MappingMethod::kLinear : MappingMethod::kCycleGan;
    const bool facs = !a->units.empty();
    const std::vector<ActionUnitTarget> units =
        facs ? parse_action_unit_targets(a->units) : std::vector<ActionUnitTarget>{};
    a->options.description =
        (facs ? "FACS units " + describe(units) : std::string("neutral to ") + to_string(to)) + " (eval)";
    const TransformEval r = facs ? evaluate_unit_edit(model, a->video, units, a->options, a->output)
                                 : evaluate_transform(model, a->video, to, a->options, a->output);
    const double n = std::max(1, r.timings.frames);
    const auto emotion_only = [facs](double value) { return facs ? nlohmann::json(nullptr) : nlohmann::json(value); };
    nlohmann::json unit_rows = nlohmann::json::array();
    for (const UnitEditMeasure& u : r.units) {
      const ActionUnit& unit = action_units()[size_t(action_unit_index(u.asked.number))];
      unit_rows.push_back({{"unit", unit.label()},
                           {"name", unit.name},
                           {"asked", u.asked.intensity},
                           {"input", u.input},
                           {"output", u.output},
                           {"retracked", u.retracked}});
    }
    print_json({{"video", a->video},
                {"to", facs ? nlohmann::json(nullptr) : nlohmann::json(to_string(to))},
                {"method", facs ? "facs-units" : a->method},
                {"lip_weight", a->options.transform.lips.alpha},
                {"units", facs ? unit_rows : nlohmann::json(nullptr)},
                {"frames", r.frames},
                {"valid_frames", r.valid_frames},
                {"lip_error_mm", r.lip_error_mm},
                {"lip_error_max_mm", r.lip_error_max_mm},
                {"target_rise", emotion_only(r.target_rise)},
                {"retracked_rise", emotion_only(r.retracked_rise)},
                {"eye_opening_change", emotion_only(r.eye_opening_change)},
                {"gaze_change", r.gaze_change},
                {"smoothness", r.smoothness},
                {"smoothness_raw", r.smoothness_raw},
                {"smoothness_mapped", r.smoothness_mapped},
                {"input_audio", r.input_audio},
                {"audio_ok", r.input_audio ? nlohmann::json(r.audio_ok) : nlohmann::json(nullptr)},
                {"audio_seconds_in", r.audio_seconds_in},
                {"audio_seconds_out", r.audio_seconds_out},
                {"marked_synthetic", r.marked_synthetic},
                {"mapping_ms_per_frame", r.timings.mapping_ms / n},
                {"render_ms_per_frame", r.timings.render_ms / n}});
  });
}

void register_eval_swap(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand(
      "swap",
      "Face-swap measures as JSON: --self VIDEO (first frame swapped into the rest: photometric error against the "
      "video), or --source PHOTO --target VIDEO (identity and expression of the tracked output, seam ratio)");
  struct Args {
    std::string self, source, target, output;
    SwapJobOptions options;
    int self_source_frames = 1;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--self", a->self, "Video: its first frame is the source, the rest the target");
  cmd->add_option("--source-frames", a->self_source_frames,
                  "--self: the source is the video's first N frames as photos (identity from all N, appearance "
                  "from the first); 1 is the single photo of the paper's experiment")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  cmd->add_option("--source", a->source, "Source portrait photo");
  cmd->add_option("--target", a->target, "Target video");
  cmd->add_option("--max-frames", a->options.capture.max_frames, "Stop after this many frames")
      ->check(whole_number_at_least(0));
  add_fit_options(*cmd, a->options.capture);
  cmd->add_option("-o,--output", a->output, "Keep the swapped video here (--source/--target; default: temporary)");
  cmd->add_flag("--wrinkles", a->options.swap.wrinkles, "Predict the target's expression wrinkles (§6.1.2)");
  add_swap_texture_flags(*cmd, a->options.swap);
  cmd->callback([a, &global] {
    const bool self = !a->self.empty();
    if (self == (!a->source.empty() || !a->target.empty()))
      throw CLI::ValidationError("eval swap needs either --self VIDEO, or --source PHOTO and --target VIDEO");
    if (!self && (a->source.empty() || a->target.empty()))
      throw CLI::ValidationError("--source and --target go together");
    const FaceModel model = load_model(global);
    a->options.capture.quiet = global.quiet;
    if (self) {
      const SwapSelfEval r = evaluate_swap_self(model, a->self, a->options, a->self_source_frames);
      const double n = std::max(1, r.timings.swapped);
      print_json({{"video", a->self},
                  {"mode", "self"},
                  {"source_frames", r.source_frames_used},
                  {"frames", r.frames},
                  {"photometric_median", r.photometric_median},
                  {"photometric_mean", r.photometric_mean},
                  {"face_pixels_per_frame", r.face_pixels_per_frame},
                  {"photometric_mean_mouth", r.regions[0].mean},
                  {"photometric_mean_eyes", r.regions[1].mean},
                  {"photometric_mean_rest", r.regions[2].mean},
                  {"pixel_share_mouth", r.regions[0].share},
                  {"pixel_share_eyes", r.regions[1].share},
                  {"covered_mean", r.covered_mean},
                  {"covered_max", r.covered_max},
                  {"render_ms_per_frame", r.timings.swap.render_ms / n},
                  {"warp_ms_per_frame", r.timings.swap.warp_ms / n},
                  {"blend_ms_per_frame", r.timings.swap.blend_ms / n}});
      return;
    }
    const SwapPairEval r = evaluate_swap_pair(model, a->source, a->target, a->options, a->output);
    print_json({{"source", a->source},
                {"target", a->target},
                {"mode", "pair"},
                {"frames", r.frames},
                {"faces_in_source", r.faces_in_source},
                {"identity_distance_output_source", r.identity_distance_output_source},
                {"identity_distance_output_target", r.identity_distance_output_target},
                {"identity_distance_source_target", r.identity_distance_source_target},
                {"identity_closer_to_source", r.identity_distance_output_source < r.identity_distance_output_target},
                {"identity_alike_output_source", r.identity_alike_output_source},
                {"identity_alike_output_target", r.identity_alike_output_target},
                {"identity_alike_source_target", r.identity_alike_source_target},
                {"identity_alike_frames", r.identity_alike_frames},
                {"shape_alike_output_source_mm", r.shape_alike_output_source_mm},
                {"shape_alike_output_target_mm", r.shape_alike_output_target_mm},
                {"shape_alike_source_target_mm", r.shape_alike_source_target_mm},
                {"expression_correlation", r.expression_correlation},
                {"expression_weights_compared", r.expression_weights_compared},
                {"seam_ratio", r.seam_ratio},
                {"seam_ratio_target", r.seam_ratio_target},
                {"hue_beyond_target_cool", r.hue_beyond_cool},
                {"hue_beyond_target_warm", r.hue_beyond_warm},
                {"covered_mean", r.covered_mean},
                {"covered_max", r.covered_max}});
  });
}

}  // namespace

void register_eval(CLI::App& app, GlobalOptions& global) {
  auto* eval = app.add_subcommand("eval", "Measure accuracy against ground truth; prints one JSON object");
  eval->require_subcommand(1);
  register_eval_landmarks(*eval, global);
  register_eval_track(*eval, global);
  register_eval_refine(*eval, global);
  register_eval_transform(*eval, global);
  register_eval_swap(*eval, global);
}

}  // namespace facecap::cli
