#include "facecap/pipeline/demo.hpp"

#include <algorithm>
#include <optional>

#include "facecap/core/rigid_alignment.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/expr/action_units.hpp"
#include "facecap/pipeline/track_job.hpp"
#include "facecap/synth/synthesize.hpp"

namespace facecap {

nlohmann::json run_demo(const FaceModel& model, const DemoOptions& options) {
  std::optional<TempDir> temp;
  std::filesystem::path dir = options.keep_dir;
  if (dir.empty()) {
    temp.emplace("facecap-demo");
    dir = temp->path();
  }
  // 1. A synthetic performance with known parameters.
  SynthOptions so;
  so.frames = options.frames;
  so.seed = options.seed;
  so.width = 1280;
  so.height = 720;
  const SynthJobResult synth = synthesize(model, so, dir, options.quiet);
  const SynthPerformance& truth = synth.ground_truth.performance;

  // 2. The capture pipeline on the rendered video, as a user would run it,
  //    compared with the truth frame by frame.
  const std::filesystem::path track_dir = dir / "track";
  std::vector<double> rotation, vertex, vertex_similarity, nme, weights, units;
  const ActionUnitReader action_units(model.expression_names);
  int lost = 0;
  TrackOptions to;
  to.capture.quiet = options.quiet;
  to.overlay = !options.keep_dir.empty();
  to.on_frame = [&](const CapturedFrame& f) {
    if (f.status == TrackStatus::kLost) {
      ++lost;
      return;
    }
    const SynthFrame& t = truth.frames[f.index];
    rotation.push_back(rotation_angle_deg(f.fit.pose.rotation_matrix(), t.pose.rotation_matrix()));
    const Positions fitted = model.evaluate(f.identity.identity.cast<float>(), f.fit.expression, regions::kFace);
    const Positions true_shape = model.evaluate(truth.identity, t.expression, regions::kFace);
    vertex.push_back(10.0 * aligned_mean_distance(fitted, true_shape));
    vertex_similarity.push_back(10.0 * aligned_mean_distance(fitted, true_shape, true));
    nme.push_back(landmark_nme(f.fit.observed, synth.ground_truth.landmarks[f.index]));
    weights.push_back((f.fit.expression - t.expression).cwiseAbs().mean());
    units.push_back(
        (action_units.intensities(f.fit.expression) - action_units.intensities(t.expression)).cwiseAbs().mean());
  };
  const TrackSummary summary = run_track(model, synth.video.string(), track_dir, to);
  const CaptureSummary& cs = summary.capture;

  nlohmann::json report;
  // The paths only where they outlive the run (--keep).
  const bool kept = !options.keep_dir.empty();
  report["input"] = {{"video", kept ? synth.video.string() : "(deleted; --keep DIR keeps it)"},
                     {"frames", options.frames},
                     {"size", "1280x720"},
                     {"seed", options.seed},
                     {"kept_in", kept ? dir.string() : ""}};
  report["capture"] = {{"frames", cs.frames},
                       {"lost_frames", lost},
                       {"fps_after_setup", cs.timings.fps()},
                       {"outputs", kept ? track_dir.string() : "(deleted; --keep DIR keeps them)"}};
  report["recovered_vs_truth"] = {
      {"focal_px", cs.identity.focal},
      {"focal_true_px", truth.camera.focal},
      {"focal_error_rel", std::abs(cs.identity.focal - truth.camera.focal) / truth.camera.focal},
      {"rotation_error_deg_median", median(rotation)},
      {"vertex_error_mm_median", median(vertex)},
      {"vertex_error_similarity_mm_median", median(vertex_similarity)},
      {"weights_mae_median", median(weights)},
      {"action_units_mae_median", median(units)},  // FACS intensity, 0-5 (action_units.hpp)
      {"dlib_landmark_nme_vs_truth_median", median(nme)}};
  report["note"] =
      "Landmarks come from dlib on the rendered video, as on real footage; `facecap eval track` measures the fit "
      "from the true landmarks as well.";
  return report;
}

}  // namespace facecap
