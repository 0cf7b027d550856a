#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/pipeline/swap_job.hpp"
#include "facecap/pipeline/transform_job.hpp"
#include "facecap/refine/displacement_bench.hpp"

namespace facecap::cli {

namespace {

// What `cover_flow_frames` counts, in both edits' benchmarks.
constexpr const char* kCoverFlowNote =
    "frames whose moving covers ran their optical flow: only where some patch of the face changed colour since the "
    "frame before, or a cover found earlier is being carried";

nlohmann::json timings_json(const StageTimings& t) {
  const double n = std::max(1, t.frames);
  return {{"frames", t.frames},
          {"setup_ms", t.setup_ms},
          {"decode_ms_per_frame", t.decode_ms / n},
          {"detect_ms_per_frame", t.detect_ms / n},
          {"landmarks_ms_per_frame", t.landmarks_ms / n},
          {"gaze_ms_per_frame", t.iris_ms / n},
          {"fit_ms_per_frame", t.fit_ms / n},
          {"identity_solve_ms", t.identity_ms},
          {"total_s", t.total_s},
          {"fps", t.fps()},
          {"fps_including_setup", t.total_s > 0 ? t.frames / t.total_s : 0.0},
          {"note",
           "decode runs on its own thread, concurrently with detection, landmarks and fit; the fit (and gaze) of a "
           "frame runs beside the next frame's detection and landmarks"}};
}

// An edit's CPU budget per frame (core/cpu_time.hpp): its own threads'
// `parts`, then the encoder's, the pool's and facecap's as a whole, each
// over `frames`, with `note` saying what the parts hold.
nlohmann::json cpu_budget_json(const std::vector<std::pair<std::string, double>>& parts, const JobCpu& job,
                               double frames, const std::string& note) {
  nlohmann::json j;
  for (const auto& [name, ms] : parts) j[name] = ms / frames;
  j["encoder"] = job.encoder_ms / frames;
  j["pool"] = job.pool_ms / frames;
  j["facecap"] = job.process_ms / frames;
  j["note"] = note;
  return j;
}

}  // namespace

void register_bench_transform(CLI::App& bench, GlobalOptions& global);

// The timings of an --all-faces pass: the shared stages (decoding, the
// whole-frame searches) at the top, each face's under "faces".
nlohmann::json all_faces_json(const AllFacesSummary& all) {
  nlohmann::json j = timings_json(all.timings);
  for (const char* per_face : {"landmarks_ms_per_frame", "gaze_ms_per_frame", "fit_ms_per_frame", "identity_solve_ms"})
    j.erase(per_face);
  j["note"] = "shared by the faces: decoding (own thread) and the whole-frame searches (detect); fps is for all faces";
  nlohmann::json faces = nlohmann::json::array();
  for (size_t k = 0; k < all.faces.size(); ++k) {
    nlohmann::json f = timings_json(all.captures[k].timings);
    for (const char* shared : {"setup_ms", "decode_ms_per_frame", "total_s", "fps", "fps_including_setup", "note"})
      f.erase(shared);
    f["first_frame"] = all.faces[k].first_frame;
    f["lost_frames"] = all.captures[k].lost;
    faces.push_back(f);
  }
  j["faces"] = faces;
  return j;
}
void register_bench_swap(CLI::App& bench, GlobalOptions& global);
void register_bench_displacement(CLI::App& bench);

void register_bench(CLI::App& app, GlobalOptions& global) {
  auto* bench = app.add_subcommand("bench", "Measure speed: per-stage milliseconds and frames per second (JSON)");
  bench->require_subcommand(1);
  auto* track = bench->add_subcommand("track", "Coarse tracking of an input, no output files");
  struct Args {
    std::string input;
    CaptureOptions capture;
    bool refine = false, all_faces = false;
    RefineOptions refine_options;
  };
  auto a = std::make_shared<Args>();
  track->add_option("INPUT", a->input, "Video file, image folder or cam:N")->required();
  CLI::Option* all_faces =
      track->add_flag("--all-faces", a->all_faces,
                      "Every face, on one decoding pass (as track --all-faces): the shared stages, then each face's");
  add_device_option(*track, a->refine_options.device);
  add_frame_range_options(*track, a->capture);
  add_smooth_frames_option(*track, a->capture.fit.smooth_frames);
  track
      ->add_flag("--refine", a->refine,
                 "Also the shading refinement, on its own thread (lighting, albedo, each level's displacement solve)")
      ->excludes(all_faces);
  track->callback([a, &global] {
    const FaceModel model = load_model(global);
    auto source = open_input(a->input, a->capture.start_seconds);
    a->capture.quiet = true;
    if (a->all_faces) {
      const AllFacesSummary all =
          run_capture_all_faces(model, *source, a->capture, {},
                                [](const FoundFace&, const InputInfo&) { return [](const CapturedFrame&) {}; });
      nlohmann::json j = all_faces_json(all);
      j["input"] = a->input;
      j["width"] = all.input.width;
      j["height"] = all.input.height;
      j["cores"] = std::thread::hardware_concurrency();
      print_json(j);
      return;
    }
    a->capture.keep_images = a->refine;
    // Refinement timings, summed on the stage's thread.
    double lighting = 0, albedo = 0, pyramid = 0, sampling = 0, steady = 0;
    std::vector<double> levels, solves;
    int refined = 0, steady_frames = 0;
    std::unique_ptr<RefineStage> stage;
    if (a->refine) {
      stage = std::make_unique<RefineStage>(model, a->refine_options, [&](const RefinedFrame& r) {
        if (!r.refinement) return;
        const RefineTimings& t = r.refinement->timings;
        lighting += t.lighting_ms;
        albedo += t.albedo_ms;
        pyramid += t.pyramid_ms;
        sampling += t.sampling_ms;
        levels.resize(std::max(levels.size(), t.level_ms.size()), 0.0);
        solves.resize(levels.size(), 0.0);
        double frame_ms = t.pyramid_ms + t.lighting_ms + t.albedo_ms;
        for (size_t l = 0; l < t.level_ms.size(); ++l) {
          levels[l] += t.level_ms[l];
          solves[l] += t.solve_ms[l];
          frame_ms += t.level_ms[l];
        }
        if (t.albedo_fixed) {
          steady += frame_ms;
          ++steady_frames;
        }
        ++refined;
      });
    }
    const auto start = std::chrono::steady_clock::now();
    const CaptureSummary s = run_capture(model, *source, a->capture, [&](const CapturedFrame& f) {
      if (stage) stage->push(f);
    });
    if (stage) stage->finish();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json j = timings_json(s.timings);
    if (stage) {
      const double n = std::max(1, refined);
      nlohmann::json per_level = nlohmann::json::array(), solve_per_level = nlohmann::json::array();
      for (double v : levels) per_level.push_back(v / n);
      for (double v : solves) solve_per_level.push_back(v / n);
      j["refine"] = {{"frames", refined},
                     {"pyramid_ms_per_frame", pyramid / n},
                     {"lighting_ms_per_frame", lighting / n},
                     {"albedo_ms_per_frame", albedo / n},
                     {"albedo_note", "the albedo is solved during the first frames only (every 3rd of the first 30)"},
                     {"timings_note",
                      "displacement_ms_per_level: a level's whole pass (its base, normals, samples, masks and solve); "
                      "displacement_solve_ms_per_level: the solve alone; sampling_ms_per_frame: every vertex sampling "
                      "(lighting and levels); total_ms_per_frame_albedo_fixed: the frames after the albedo is fixed"},
                     {"displacement_ms_per_level", per_level},
                     {"displacement_solve_ms_per_level", solve_per_level},
                     {"sampling_ms_per_frame", sampling / n},
                     {"total_ms_per_frame", stage->refine_ms() / n},
                     {"total_ms_per_frame_albedo_fixed", steady / std::max(1, steady_frames)},
                     {"device", to_string(a->refine_options.device)}};
      // Whether the two stages overlap: the stage's thread idles until
      // capture's start-up (the identity solve over the first frames) hands
      // it the first frame, and from then on either waits for frames (capture
      // is the bottleneck) or makes capture wait in push() (it is).
      const RefineStageTimings& st = stage->timings();
      const double m = std::max(1, stage->frames());
      j["refine_stage"] = {{"frames", stage->frames()},
                           {"startup_ms", st.startup_ms},
                           {"first_refine_ms", st.first_refine_ms},
                           {"coarse_face_ms_per_frame", st.coarse_ms / m},
                           {"consumer_ms_per_frame", st.consumer_ms / m},
                           {"idle_ms_per_frame", st.idle_ms / m},
                           {"capture_blocked_ms_per_frame", st.push_wait_ms / m},
                           {"fps_after_startup", st.first_to_last_ms > 0 ? 1000.0 * m / st.first_to_last_ms : 0.0}};
      j["fps_with_refine"] =
          (wall - s.timings.setup_ms / 1000) > 0 ? s.frames / (wall - s.timings.setup_ms / 1000) : 0.0;
    }
    j["input"] = a->input;
    j["width"] = s.input.width;
    j["height"] = s.input.height;
    j["lost_frames"] = s.lost;
    j["cores"] = std::thread::hardware_concurrency();
    print_json(j);
  });
  register_bench_transform(*bench, global);
  register_bench_swap(*bench, global);
  register_bench_displacement(*bench);
}

void register_bench_swap(CLI::App& bench, GlobalOptions& global) {
  auto* cmd = bench.add_subcommand("swap", "Face swap into a scratch file: per-stage ms and the swap's fps");
  struct Args {
    std::string source, target;
    int max_frames = 120;
    bool all_faces = false;
    bool tracked_first = false;
    SwapOptions swap;
    VideoEncoding encoding;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--source", a->source, "Source portrait photo")->required();
  CLI::Option* all_faces =
      cmd->add_flag("--all-faces", a->all_faces,
                    "Every face of the target, on one decoding pass (as swap --all-faces): the shared capture stages, "
                    "each face's, and the swap's summed over the faces");
  CLI::Option* tracked_first = cmd->add_flag(
      "--tracked-first", a->tracked_first,
      "Capture the whole target first, then swap it: the swap's stages timed without capture running beside them "
      "(every frame held in memory, about 2.8 MB a 720p frame); one face");
  tracked_first->excludes(all_faces);
  cmd->add_option("--target", a->target, "Target video")->required();
  cmd->add_option("--max-frames", a->max_frames, "Stop after this many frames (0: all)")
      ->check(whole_number_at_least(0))
      ->capture_default_str();
  cmd->add_flag("--wrinkles", a->swap.wrinkles, "With the wrinkle prediction of §6.1.2 (the target is refined)");
  add_swap_texture_flags(*cmd, a->swap);
  add_encoding_options(*cmd, a->encoding, "the scratch output, as swap's");
  cmd->callback([a, &global] {
    const FaceModel model = load_model(global);
    SwapJobOptions o;
    o.swap = a->swap;
    o.encoding = a->encoding;
    o.capture.max_frames = a->max_frames;
    o.capture.quiet = true;
    o.track_first = a->tracked_first;
    const TempDir scratch("facecap-bench");
    const auto start = std::chrono::steady_clock::now();
    nlohmann::json j;
    SwapJobTimings timings;
    InputInfo input;
    int frames = 0;
    if (a->all_faces) {
      const AllFacesSwapSummary s = run_swap_all_faces(model, a->source, a->target, scratch.path() / "bench.mp4", o);
      j = all_faces_json(s.target);
      timings = s.timings;
      input = s.target.input;
      frames = s.target.timings.frames;
    } else {
      const SwapSummary s = run_swap(model, a->source, a->target, scratch.path() / "bench.mp4", o);
      j = timings_json(s.target.timings);
      timings = s.timings;
      input = s.target.input;
      frames = s.target.frames;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double n = std::max(1, timings.swapped);
    const SwapTimings& t = timings.swap;
    const double steady_ms = (t.render_ms + t.wrinkle_ms + t.ratio_ms + t.occlusion_ms + t.warp_ms + t.blend_ms) / n;
    const double with_appearance_ms = steady_ms + t.appearance_ms / n;
    j["swap"] = {
        {"frames", timings.swapped},
        {"frames_note", "frames swapped; with --all-faces, summed over the faces, as are the timings"},
        {"source_reconstruction_ms", timings.source_ms},
        {"appearance_ms_per_frame", t.appearance_ms / n},
        {"appearance_note", "texture of the target face and harmonisation, first frames only"},
        {"render_ms_per_frame", t.render_ms / n},
        {"warp_ms_per_frame", t.warp_ms / n},
        {"blend_ms_per_frame", t.blend_ms / n},
        {"wrinkle_ms_per_frame", t.wrinkle_ms / n},
        {"wrinkle_setup_ms", t.wrinkle_setup_ms},
        {"wrinkle_setup_note",
         "the coating transfer's factorisation on the first frame (of each shot), not in the fps"},
        {"expression_ratio_ms_per_frame", t.ratio_ms / n},
        {"occlusion_ms_per_frame", t.occlusion_ms / n},
        {"cover_flow_frames", t.flow_frames},
        {"cover_flow_note", kCoverFlowNote},
        {"swap_ms_per_frame", steady_ms},
        {"swap_fps", steady_ms > 0 ? 1000.0 / steady_ms : 0.0},
        {"swap_fps_with_appearance", with_appearance_ms > 0 ? 1000.0 / with_appearance_ms : 0.0},
        {"lighting_ms_per_frame", timings.lighting_ms / n},
        {"lighting_note", "the target's SH lighting, and with --wrinkles its displacement solve"},
        {"preparation_ms_per_frame", timings.preparation_ms / n},
        {"preparation_note",
         "the target unshaded for the occlusion mask and its moving covers (optical flow), on the "
         "lighting stage's second thread beside the swap of the frame before (not in swap_ms_per_frame)"},
        {"cpu_ms_per_frame",
         cpu_budget_json({{"swap_thread", timings.swap_thread_cpu_ms},
                          {"preparation", timings.preparation_cpu_ms},
                          {"lighting", timings.lighting_cpu_ms}},
                         timings.job_cpu, n,
                         "CPU time per frame swapped, where the ms above are wall times that include waiting for a "
                         "core: the swap's own thread (the swap and its frame's writing, appearance frames "
                         "included), the preparation's and the lighting's, the encoder process (audio included), "
                         "the pool's workers (on every stage's loops, capture's too unless --tracked-first), and "
                         "facecap's threads all together (the same share; the encoder is another process). The "
                         "threads' sum against the cores times swap_ms_per_frame says whether the cores were "
                         "full")},
        {"tracked_first", a->tracked_first},
        {"timing_note", a->tracked_first
                            ? "the target was captured first: the swap's stages ran without capture beside them"
                            : "the swap's stages are wall times on its thread, capture running beside them "
                              "(--tracked-first times them alone)"}};
    j["fps_end_to_end"] = wall > 0 ? frames / wall : 0.0;
    j["width"] = input.width;
    j["height"] = input.height;
    j["cores"] = std::thread::hardware_concurrency();
    print_json(j);
  });
}

void register_bench_transform(CLI::App& bench, GlobalOptions& global) {
  auto* cmd = bench.add_subcommand(
      "transform", "Expression transformation of an input into a scratch file: per-stage ms and the edit's fps");
  struct Args {
    std::string input, to = "happiness";
    int max_frames = 150;
    bool all_faces = false;
    VideoEncoding encoding;
    CoverOptions covers;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUT", a->input, "Video file or image folder")->required();
  cmd->add_option("--to", a->to, std::string("Target expression: ") + emotion_choices())
      ->check(emotion_value())
      ->capture_default_str();
  cmd->add_flag("--all-faces", a->all_faces,
                "Every face, on one decoding pass (as transform --all-faces): the shared capture stages, each "
                "face's, and the edit's summed over the faces");
  cmd->add_option("--max-frames", a->max_frames, "Stop after this many frames (0: all)")
      ->check(whole_number_at_least(0))
      ->capture_default_str();
  add_encoding_options(*cmd, a->encoding, "the scratch output, as transform's");
  add_transform_cover_flags(*cmd, a->covers);
  cmd->callback([a, &global] {
    const Emotion to = emotion_argument("--to", a->to);
    const FaceModel model = load_model(global);
    TransformJobOptions o;
    o.encoding = a->encoding;
    o.covers = a->covers;
    o.capture.max_frames = a->max_frames;
    o.capture.quiet = true;
    o.transform.schedule = ExpressionSchedule::constant(to, 1.0);
    o.description = "benchmark";
    const TempDir scratch("facecap-bench");
    const auto start = std::chrono::steady_clock::now();
    nlohmann::json j;
    TransformTimings timings;
    InputInfo input;
    if (a->all_faces) {
      const AllFacesTransformSummary s = run_transform_all_faces(model, a->input, scratch.path() / "bench.mp4", o);
      j = all_faces_json(s.capture);
      timings = s.timings;
      input = s.capture.input;
    } else {
      const TransformSummary s = run_transform(model, a->input, scratch.path() / "bench.mp4", o);
      j = timings_json(s.capture.timings);
      timings = s.timings;
      input = s.capture.input;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double n = std::max(1, timings.frames);
    const double edit_ms = (timings.mapping_ms + timings.render_ms + timings.covers_ms) / n;
    j["transform"] = {
        {"frames", timings.frames},
        {"mapping_smoothing_qp_ms_per_frame", timings.mapping_ms / n},
        {"rerender_composite_ms_per_frame", timings.render_ms / n},
        {"covers_ms_per_frame", timings.covers_ms / n},
        {"cover_preparation_ms_per_frame", timings.cover_preparation_ms / n},
        {"cover_flow_frames", timings.cover_flow_frames},
        {"cover_flow_note", kCoverFlowNote},
        {"edit_ms_per_frame", edit_ms},
        {"edit_fps", edit_ms > 0 ? 1000.0 / edit_ms : 0.0},
        {"lighting_ms_per_frame", timings.lighting_ms / n},
        {"cpu_ms_per_frame",
         cpu_budget_json({{"edit_thread", timings.edit_thread_cpu_ms},
                          {"lighting", timings.lighting_cpu_ms},
                          {"cover_preparation", timings.cover_preparation_cpu_ms}},
                         timings.job_cpu, n,
                         "CPU time per frame, where the ms above are wall times that include waiting "
                         "for a core: the edit's thread (mapping, re-render, composite and the "
                         "frame's writing) and the lighting's, the encoder process (audio included), "
                         "the pool's workers (capture's loops too), and facecap's threads all "
                         "together (decoding and capture included; the encoder is another process). "
                         "facecap plus encoder against the cores times the run's wall time says "
                         "whether the cores were full")},
        {"note",
         "edit = mapping + smoothing + lip QP + re-render + composite + covers (what covers the face, kept in "
         "front; its unshading and optical flow run beside, on the lighting's stage: cover_preparation); lighting is "
         "the refinement's SH estimate (albedo over the first 4 frames); with --all-faces, each summed over the "
         "faces (their streams run on threads of their own)"}};
    j["fps_end_to_end"] = wall > 0 ? timings.frames / wall : 0.0;
    j["input"] = a->input;
    j["width"] = input.width;
    j["height"] = input.height;
    j["cores"] = std::thread::hardware_concurrency();
    print_json(j);
  });
}

void register_bench_displacement(CLI::App& bench) {
  auto* cmd = bench.add_subcommand(
      "displacement",
      "The displacement solve alone on saved problems (`facecap eval refine --video V --save-problems DIR`): "
      "milliseconds per level on each device and, on a machine with a GPU, the CUDA results against the CPU");
  struct Args {
    std::string dir, device;
    bool check = false;
    DisplacementBenchOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("DIR", a->dir, "Folder of .fcdp problem files")->required();
  cmd->add_option("--device", a->device,
                  "cpu, cuda, or both (the CPU is then the reference); default: both where a GPU answers, else cpu")
      ->check(CLI::IsMember({"cpu", "cuda", "both"}));
  cmd->add_option("--repeats", a->options.repeats, "Timed solves per problem (the median is kept)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_flag("--check", a->check,
                "Exit with status 1 unless the CUDA results agree with the CPU (needs both devices)");
  cmd->callback([a] {
    const std::string device = a->device.empty() ? (cuda_device_available() ? "both" : "cpu") : a->device;
    if (device != "cpu" && !cuda_device_available())
      throw Error(cuda_built() ? "--device " + device + ": no CUDA device answers on this machine"
                               : "--device " + device + ": this facecap was built without CUDA");
    if (device != "cuda") a->options.devices.push_back(ComputeDevice::cpu);
    if (device != "cpu") a->options.devices.push_back(ComputeDevice::cuda);
    if (a->check && a->options.devices.size() < 2) throw Error("--check needs --device both (and a GPU)");
    const DisplacementBenchResult r = bench_displacement(a->dir, a->options);
    nlohmann::json j = {{"problems", r.problems},
                        {"frames", r.frames},
                        {"levels", r.levels},
                        {"free_vertices_per_level", r.level_vertices},
                        {"gauss_newton_steps", a->options.solver.gauss_newton_steps},
                        {"pcg_iterations", a->options.solver.pcg_iterations}};
    for (const DeviceTiming& t : r.timings) {
      j[std::string(to_string(t.device))] = {
          {"ms_per_level", t.level_ms}, {"ms_per_frame", t.frame_ms}, {"max_ms_per_frame", t.max_frame_ms}};
    }
    bool agree = true;
    if (r.compared) {
      const DeviceAgreement& g = r.agreement;
      agree = g.within_tolerance();
      j["agreement"] = {
          {"max_abs_diff_um", g.max_abs_diff_um},
          {"max_rel_diff", g.max_rel_diff},
          {"max_cost_rel_diff", g.max_cost_rel_diff},
          {"same_gauss_newton_steps", g.same_steps},
          {"agree", agree},
          {"tolerance", {{"rel_diff", DeviceAgreement::kRelDiff}, {"cost_rel_diff", DeviceAgreement::kCostRelDiff}}}};
      if (r.timings.size() == 2 && r.timings[1].frame_ms > 0)
        j["speedup"] = r.timings[0].frame_ms / r.timings[1].frame_ms;
    }
    print_json(j);
    if (a->check && !agree) throw Error("the CUDA displacement solve disagrees with the CPU reference");
  });
}

}  // namespace facecap::cli
