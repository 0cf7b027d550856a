#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/pipeline/landmark_eval.hpp"
#include "facecap/pipeline/synth_landmark_eval.hpp"

namespace facecap::cli {

namespace {

void register_eval_landmarks(CLI::App& eval, GlobalOptions& global) {
  auto* cmd = eval.add_subcommand("landmarks",
                                  "Landmark accuracy as JSON: dlib's 68 points on an annotated image (IMAGE PTS), "
                                  "or detection rate and NME on synthetic renders (--synthetic N)");
  struct Args {
    std::string image, pts;
    int synthetic = 0;
    uint64_t seed = 1;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("IMAGE", a->image, "Image file");
  cmd->add_option("PTS", a->pts, "iBUG .pts annotation (1-based coordinates)");
  cmd->add_option("--synthetic", a->synthetic, "Render N synthetic frames instead and score against their truth");
  cmd->add_option("--seed", a->seed, "Seed of the synthetic performance")->capture_default_str();
  cmd->callback([a, &global] {
    if (a->synthetic > 0) {
      const FaceModel model = load_model(global);
      SynthOptions o;
      o.frames = a->synthetic;
      o.seed = a->seed;
      const SynthLandmarkEval r = evaluate_synthetic_landmarks(model, o, global.quiet);
      print_json({{"frames", r.frames},
                  {"detected", r.detected},
                  {"detection_rate", r.detection_rate},
                  {"nme_median", r.nme_median},
                  {"nme_mean", r.nme_mean},
                  {"nme_inner_median", r.nme_inner_median}});
      return;
    }
    if (a->image.empty() || a->pts.empty()) throw Error("eval landmarks needs IMAGE and PTS, or --synthetic N");
    const LandmarkEvalResult r = evaluate_landmarks(a->image, a->pts);
    print_json({{"image", a->image},
                {"faces", r.faces},
                {"nme", r.nme},
                {"mean_error_px", r.mean_error_px},
                {"max_error_px", r.max_error_px},
                {"nme_jaw", r.nme_jaw},
                {"nme_brows", r.nme_brows},
                {"nme_nose", r.nme_nose},
                {"nme_eyes", r.nme_eyes},
                {"nme_mouth", r.nme_mouth}});
  });
}

}  // namespace

void register_eval(CLI::App& app, GlobalOptions& global) {
  auto* eval = app.add_subcommand("eval", "Measure accuracy against ground truth; prints one JSON object");
  eval->require_subcommand(1);
  register_eval_landmarks(*eval, global);
}

}  // namespace facecap::cli
