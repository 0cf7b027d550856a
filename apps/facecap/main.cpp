// facecap: real-time face capture and manipulation from ordinary RGB video.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <opencv2/core/utils/logger.hpp>

#include "commands.hpp"
#include "facecap/core/allocator_tuning.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/core/version.hpp"

int main(int argc, char** argv) {
  using namespace facecap;
  keep_large_allocations_resident();
  // OpenCV's own warnings (a camera that does not open, GStreamer's fallback)
  // would add lines to our one-line errors; OPENCV_LOG_LEVEL still chooses.
  if (std::getenv("OPENCV_LOG_LEVEL") == nullptr) cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
  CLI::App app{"facecap " + std::string(kFacecapVersion) +
               ": capture a face from RGB video: head pose, focal length, identity, 53 expression\n"
               "weights, and with --refine SH lighting, albedo and wrinkle-level geometry.\n"
               "Every subcommand has --help."};
  app.set_version_flag("--version", std::string(kFacecapVersion));
  app.require_subcommand(1);
  cli::GlobalOptions global;
  app.add_option("--model-dir", global.model_dir,
                 "ICT face model folder (default: $FACECAP_MODEL_DIR or ../shared/models/ict-facekit)");
  app.add_flag("-q,--quiet", global.quiet, "No progress output on stderr");
  install_interrupt_handler();
  cli::register_probe(app, global);
  cli::register_track(app, global);
  cli::register_transform(app, global);
  cli::register_swap(app, global);
  cli::register_model(app, global);
  cli::register_synth(app, global);
  cli::register_eval(app, global);
  cli::register_demo(app, global);
  cli::register_bench(app, global);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Prints the help, the version or the usage error; usage errors exit
    // with 2 (CLI11's own codes, 105-109, tell a script nothing more).
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const Error& e) {
    std::fprintf(stderr, "facecap: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facecap: unexpected error: %s\n", e.what());
    return 1;
  }
  return 0;
}
