#include <cstdio>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/synth/synthesize.hpp"

namespace facecap::cli {

void register_synth(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("synth",
                                 "Render a synthetic performance with known parameters: DIR/video.mp4, "
                                 "DIR/truth.json (every parameter per frame), DIR/albedo.png");
  struct Args {
    std::string out;
    std::string size = "640x480";
    SynthOptions options;
    std::string face_photo;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-o,--output", a->out, "Output folder")->required();
  cmd->add_option("--frames", a->options.frames, "Number of frames")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Random seed (identity, motion, lighting, albedo)")->capture_default_str();
  cmd->add_option("--size", a->size, "Frame size WxH")->check(synthetic_frame_size())->capture_default_str();
  cmd->add_option("--fps", a->options.fps, "Frame rate")->check(number_between(0.1, 240))->capture_default_str();
  cmd->add_option("--focal", a->options.focal, "Focal length in pixels (default, or 0: 1.1 x width)")
      ->check(number_between(0, 100000));
  cmd->add_option("--yaw", a->options.max_yaw_deg, "Head turns sweep +-this many degrees")
      ->check(number_between(0, 60))
      ->capture_default_str();
  cmd->add_option("--roll", a->options.camera_roll_deg,
                  "The camera turned about its axis by this many degrees (90: on its side): the performance rolls in "
                  "the image, clockwise")
      ->check(number_between(-180, 180))
      ->capture_default_str();
  cmd->add_flag("--still", a->options.still, "Hold pose and expression (for jitter measurements)");
  cmd->add_flag("--detail", a->options.detail, "Add wrinkle-like displacements along the normals");
  cmd->add_option("--noise", a->options.noise_sigma, "Sensor noise sigma, grey levels")
      ->check(number_between(0, 50))
      ->capture_default_str();
  add_face_photo_option(*cmd, a->face_photo);
  cmd->callback([a, &global] {
    parse_size(a->size, a->options.width, a->options.height);
    a->options.check();
    const FaceModel model = load_model(global);
    use_face_photo(model, a->face_photo, a->options);
    const SynthJobResult r = synthesize(model, a->options, a->out, global.quiet);
    print_json({{"video", r.video.string()},
                {"truth", r.truth.string()},
                {"albedo", r.albedo.string()},
                {"frames", a->options.frames},
                {"seconds", r.seconds}});
  });
}

}  // namespace facecap::cli
