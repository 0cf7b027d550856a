#include <chrono>

#include "commands.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/model/model_cache.hpp"

namespace facecap::cli {

void register_model(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("model", "Load the face model, build its binary cache, and describe it as JSON");
  cmd->callback([&global] {
    const std::filesystem::path dir =
        global.model_dir.empty() ? default_model_dir() : std::filesystem::path(global.model_dir);
    ModelLoadReport report;
    const FaceModel m = load_face_model(dir, &report);
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
                {"landmarks", m.landmarks.vertices.size()}});
  });
}

}  // namespace facecap::cli
