#include "commands.hpp"
#include "facecap/pipeline/demo.hpp"

namespace facecap::cli {

void register_demo(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("demo",
                                 "The main job on the default input: synthesise a short performance with known "
                                 "parameters, capture it, and print what was recovered against the truth");
  auto opts = std::make_shared<DemoOptions>();
  cmd->add_option("--frames", opts->frames, "Frames to synthesise")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  cmd->add_option("--seed", opts->seed, "Seed of the synthetic performance")->capture_default_str();
  cmd->add_option("--keep", opts->keep_dir, "Keep the synthetic input and outputs in this folder");
  cmd->callback([opts, &global] {
    const FaceModel model = load_model(global);
    opts->quiet = global.quiet;
    print_json(run_demo(model, *opts));
  });
}

}  // namespace facecap::cli
