#include <chrono>

#include "commands.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/model/model_cache.hpp"

namespace facecap::cli {

void register_model(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand(
      "model", "Load the face model and the landmark predictor, build their binary caches, and describe them as JSON");
  cmd->callback([&global] {
    const std::filesystem::path dir =
        global.model_dir.empty() ? default_model_dir() : std::filesystem::path(global.model_dir);
    ModelLoadReport report;
    const FaceModel m = load_face_model(dir, &report);
    // The 68-point predictor keeps a flat copy in the same cache folder on its
    // first load (detect/regression_cascade.hpp): made here, by setup.sh,
    // rather than by the first capture.
    const auto landmark_start = std::chrono::steady_clock::now();
    const LandmarkDetector predictor;
    const double landmark_seconds = ms_since(landmark_start) / 1000.0;
    print_json({{"model_dir", dir.string()},
                {"cache", report.cache_file.string()},
                {"from_cache", report.from_cache},
                {"cache_written", report.cache_written},
                {"load_seconds", report.seconds},
                {"vertices", m.num_vertices},
                {"polygons", m.polygons.size()},
                {"uvs", m.uvs.size()},
                {"identity_modes", m.num_identity()},
                {"expressions", m.expression_names},
                {"landmarks", m.landmarks.vertices.size()},
                {"landmark_model", default_landmark_model_path().string()},
                {"landmark_model_load_seconds", landmark_seconds}});
  });
}

}  // namespace facecap::cli
