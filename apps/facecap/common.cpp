#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "commands.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/detect/face_tracker.hpp"
#include "facecap/expr/action_units.hpp"
#include "facecap/expr/emotions.hpp"
#include "facecap/expr/lip_correction.hpp"
#include "facecap/model/model_cache.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/identity_file.hpp"
#include "facecap/pipeline/photo_face_texture.hpp"
#include "facecap/swap/face_covers.hpp"
#include "facecap/synth/performance.hpp"

namespace facecap::cli {

FaceModel load_model(const GlobalOptions& global) {
  const std::filesystem::path dir =
      global.model_dir.empty() ? default_model_dir() : std::filesystem::path(global.model_dir);
  ModelLoadReport report;
  FaceModel model = load_face_model(dir, &report);
  if (!global.quiet) {
    std::fprintf(stderr, "model: %s (%s, %.2f s)\n", dir.string().c_str(),
                 report.from_cache ? "from cache" : (report.cache_written ? "parsed, cache written" : "parsed"),
                 report.seconds);
  }
  return model;
}

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << std::endl; }

namespace {

// "WxH" read into `w` and `h`, both positive; false otherwise.
bool read_size(const std::string& s, int& w, int& h) {
  char tail = 0;
  return std::sscanf(s.c_str(), "%dx%d%c", &w, &h, &tail) == 2 && w > 0 && h > 0;
}

}  // namespace

void parse_size(const std::string& s, int& w, int& h) {
  if (!read_size(s, w, h)) throw Error("--size must look like 640x480, got '" + s + "'");
}

Emotion emotion_argument(const std::string& option, const std::string& value) {
  const std::optional<Emotion> e = parse_emotion(value);
  if (!e) throw Error(option + " must be one of " + emotion_choices() + ", not '" + value + "'");
  return *e;
}

void add_init_frames_option(CLI::App& cmd, int& init_frames) {
  cmd.add_option("--init-frames", init_frames,
                 "Frames with a face the identity and focal length are solved from, before the first output; more "
                 "frames show more head poses, and weigh together as much as 30")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
}

CLI::Option* add_smooth_frames_option(CLI::App& cmd, int& smooth_frames) {
  return cmd
      .add_option("--smooth-frames", smooth_frames,
                  "Frames fitted forward and then smoothed backward before they come out (each tied to the next "
                  "frame as well as the previous one: steadier and without lag, this many frames later); 0 fits each "
                  "frame as it comes, tied to the one before only")
      ->check(whole_number_at_least(0))
      ->capture_default_str();
}

void add_shot_cuts_option(CLI::App& cmd, bool& shot_cuts) {
  cmd.add_flag_callback(
      "--no-shot-cuts", [&shot_cuts] { shot_cuts = false; },
      "Keep one identity and focal length for the whole input. By default a shot cut (the picture changes "
      "all at once: an edit to another speaker, another camera) starts a new shot whose identity and focal "
      "length are solved again");
}

void add_frame_range_options(CLI::App& cmd, CaptureOptions& capture) {
  cmd.add_option("--max-frames", capture.max_frames, "Stop after this many frames (0: all)")
      ->check(whole_number_at_least(0));
  add_start_option(cmd, capture.start_seconds);
}

FitCliOptions add_fit_options(CLI::App& cmd, CaptureOptions& capture) {
  add_init_frames_option(cmd, capture.fit.init_frames);
  CLI::Option* smooth = add_smooth_frames_option(cmd, capture.fit.smooth_frames);
  add_shot_cuts_option(cmd, capture.shot_cuts);
  return {smooth, add_face_option(cmd, capture.tracker.pick)};
}

CLI::Option* add_action_units_option(CLI::App& cmd, std::string& units, const std::string& help) {
  return cmd.add_option("--units", units, help)->type_name("AU=X,...")->check([](const std::string& text) {
    try {
      parse_action_unit_targets(text);
      return std::string();
    } catch (const Error& e) {
      return std::string(e.what());
    }
  });
}

CLI::Option* add_face_option(CLI::App& cmd, FacePick& pick, const std::string& name, const std::string& help) {
  return cmd
      .add_option_function<std::string>(
          name, [&pick](const std::string& text) { pick = parse_face_pick(text); },
          help.empty() ? "Which face to follow where several are in view: largest (default), left, right, or X,Y "
                         "(pixels: the face nearest that point). It chooses at the start of each shot; after a loss, "
                         "only a face where the followed one was last seen is taken up for 50 frames"
                       : help)
      ->check([](const std::string& text) {
        try {
          parse_face_pick(text);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());  // CLI11 puts the option's name before it
        }
      });
}

CLI::Option* add_all_faces_options(CLI::App& cmd, bool& all_faces, AllFacesOptions& all, const std::string& help) {
  CLI::Option* flag = cmd.add_flag("--all-faces", all_faces, help);
  cmd.add_option("--max-faces", all.max_faces, "--all-faces: capture at most this many faces")
      ->check(CLI::Range(1, 64))
      ->needs(flag)
      ->capture_default_str();
  cmd.add_option("--search-every", all.search_every,
                 "--all-faces: search the whole frame for new faces every this many frames")
      ->check(CLI::Range(1, 1000))
      ->needs(flag)
      ->capture_default_str();
  return flag;
}

void add_leave_faces_option(CLI::App& cmd, CLI::Option* all_faces, AllFacesOptions& all) {
  cmd.add_option_function<std::vector<int>>(
         "--leave-faces", [&all](const std::vector<int>& faces) { all.unedited.insert(faces.begin(), faces.end()); },
         "--all-faces: leave these faces as they are (K,K...: each face's index in the order found, as track "
         "--all-faces numbers them in DIR/faces.png)")
      ->delimiter(',')
      ->check(whole_number_at_least(0))
      ->needs(all_faces);
}

std::pair<int, std::string> parse_face_value(const std::string& text) {
  const size_t equals = text.find('=');
  const std::string usage = "must be K=VALUE (K: the face's index, 0 for the first found), not '" + text + "'";
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) throw Error(usage);
  const std::string index = text.substr(0, equals);
  if (!std::all_of(index.begin(), index.end(), [](unsigned char c) { return std::isdigit(c); }) || index.size() > 6)
    throw Error(usage);
  return {std::stoi(index), text.substr(equals + 1)};
}

CLI::Validator face_value_check(std::function<void(const std::string& value)> value) {
  return CLI::Validator(
      [value](std::string& text) {
        try {
          const auto face = parse_face_value(text);
          if (value) value(face.second);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      },
      "");
}

void report_edited_faces(const AllFacesSummary& all, const AllFacesOptions& options, const char* verb,
                         const std::function<int(int face)>& edited, const std::function<std::string(int face)>& own) {
  for (int k = 0; k < int(all.faces.size()); ++k) {
    const std::string choice = own(k);
    const std::string note = options.unedited.contains(k) ? " (--leave-faces)"
                             : choice.empty()             ? ""
                                                          : " (" + choice + ")";
    std::fprintf(stderr, "face %d (from frame %d): frames %d, %s %d, lost %d%s\n", k, all.faces[k].first_frame,
                 all.captures[k].frames, verb, edited(k), all.captures[k].lost, note.c_str());
  }
  report_damaged_input(all.damage, "the input");
}

void report_unfound_faces(const std::vector<int>& named, const AllFacesSummary& all, const char* option) {
  for (const int face : named) {
    if (face >= int(all.faces.size()))
      std::fprintf(stderr, "facecap: face %d (%s) was not found: the input showed %d face(s)\n", face, option,
                   int(all.faces.size()));
  }
}

void report_uncaptured_faces(const AllFacesSummary& all, const char* what) {
  if (all.uncaptured_faces > 0)
    std::fprintf(stderr, "facecap: up to %d more face(s) at once were %s (--max-faces %d)\n", all.uncaptured_faces,
                 what, int(all.faces.size()));
}

void report_damaged_input(const InputDamage& damage, const std::string& what) {
  for (const std::string& note : input_damage_notes(damage, what)) std::fprintf(stderr, "facecap: %s\n", note.c_str());
}

void add_matte_option(CLI::App& cmd, std::filesystem::path& matte, const std::string& what) {
  cmd.add_option(
      "--matte", matte,
      "Also write the " + what +
          "'s matte: a greyscale video (or image, for a photo) of its share of each "
          "output pixel, 255 to 0, frame for frame with the output, for compositing (with --all-faces, the "
          "largest of the faces' shares); marked as synthetic, with a sidecar MATTE.json, and without sound");
}

void add_encoding_options(CLI::App& cmd, VideoEncoding& encoding, const std::string& what, CLI::Option* needs) {
  CLI::Option* crf =
      cmd.add_option("--crf", encoding.crf,
                     "x264's quality for " + what +
                         ": 0 (lossless) to 51, lower is better and larger; 18 is visually lossless, 12 near-lossless "
                         "for compositing")
          ->check(CLI::Range(0, 51))
          ->capture_default_str();
  std::vector<std::string> presets(std::begin(kX264Presets), std::end(kX264Presets));
  CLI::Option* preset =
      cmd.add_option("--x264-preset", encoding.preset,
                     "x264's speed against file size for " + what +
                         ": a slower preset makes a smaller file at the same --crf. At 1280x720 and crf 18 x264 "
                         "takes about 5 / 9 / 12 / 32 ms of CPU a frame at ultrafast / superfast / veryfast / medium, "
                         "for files 4.8 / 2.4 / 1 / 1.1 times veryfast's")
          ->check(CLI::IsMember(presets))
          ->capture_default_str();
  if (needs) {
    crf->needs(needs);
    preset->needs(needs);
  }
}

CLI::Option* add_identity_option(CLI::App& cmd, std::optional<Eigen::VectorXd>& identity) {
  return cmd.add_option_function<std::string>(
      "--identity", [&identity](const std::string& path) { identity = read_identity_weights(path); },
      "Hold the face of an earlier capture's identity.json (facecap track) rather than solve it: takes of one "
      "person then share one face; with --focal F --focal-known the output starts at the first frame");
}

CLI::Validator whole_number_at_least(int least) {
  return CLI::Validator(
      [least](std::string& text) {
        int value = 0;
        const char* const last = text.data() + text.size();
        const auto [end, error] = std::from_chars(text.data(), last, value);
        const bool ok = error == std::errc() && end == last && value >= least;
        return ok ? std::string() : "must be a whole number of at least " + std::to_string(least) + ", not " + text;
      },
      least == 0   ? "NONNEGATIVE"
      : least == 1 ? "POSITIVE"
                   : ">=" + std::to_string(least));
}

CLI::Validator emotion_value() {
  return CLI::Validator(
      [](std::string& text) {
        return parse_emotion(text) ? std::string()
                                   : std::string("must be one of ") + emotion_choices() + ", not '" + text + "'";
      },
      "EMOTION");
}

CLI::Validator synthetic_frame_size() {
  return CLI::Validator(
      [](std::string& text) {
        int width = 0, height = 0;
        const bool ok =
            read_size(text, width, height) && width >= 64 && height >= 64 && width <= 8192 && height <= 8192;
        return ok ? std::string() : "must be WxH, 64 to 8192 a side (as 640x480), not " + text;
      },
      "WxH");
}

CLI::Validator number_between(double least, double most) {
  const std::string range = csv_number(least) + " to " + csv_number(most);
  return CLI::Validator(
      [least, most, range](std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        // NaN fails both comparisons, so it is refused with the rest.
        const bool ok = end != text.c_str() && *end == '\0' && value >= least && value <= most;
        return ok ? std::string() : "must be a number from " + range + ", not " + text;
      },
      range);
}

void add_start_option(CLI::App& cmd, double& start_seconds) {
  cmd.add_option("--start", start_seconds,
                 "Start this many seconds into the video (frames keep their own numbers and times; an output video "
                 "and its audio start there)")
      ->check(
          [](const std::string& text) {
            char* end = nullptr;
            const double seconds = std::strtod(text.c_str(), &end);
            const bool ok = end != text.c_str() && *end == '\0' && std::isfinite(seconds) && seconds >= 0;
            return ok ? std::string() : "must be 0 or more seconds, not " + text;
          },
          "SECONDS");
}

void add_device_option(CLI::App& cmd, ComputeDevice& device) {
  // `device` outlives the parse: it is part of the subcommand's arguments.
  cmd.add_option_function<std::string>(
         "--device",
         [&device](const std::string& name) {
           const std::optional<ComputeDevice> d = parse_compute_device(name);
           if (!d) throw CLI::ValidationError("--device", "must be cpu or cuda, not '" + name + "'");
           // Not a parse error: the machine lacks what was asked for (one line).
           if (*d == ComputeDevice::cuda && !cuda_device_available())
             throw Error(cuda_built() ? "--device cuda: no CUDA device answers on this machine"
                                      : "--device cuda: this facecap was built without CUDA");
           device = *d;
         },
         "Where the refinement's vertex sampling, albedo solve and displacement solve run: cpu or cuda (default: " +
             std::string(to_string(default_compute_device())) + " on this machine)")
      ->type_name("cpu|cuda");
}

void add_cover_flags(CLI::App& cmd, bool& keep_occluders, bool& moving_covers, const std::string& paint_over,
                     const std::string& cost) {
  cmd.add_flag_callback(
      "--no-occlusion", [&keep_occluders] { keep_occluders = false; }, paint_over + " rather than leave it in front");
  cmd.add_flag_callback(
      "--no-moving-covers", [&moving_covers] { moving_covers = false; },
      "Find covers by their colour alone: not a hand of the skin's own colour moving across the face, which the "
      "optical flow finds (" +
          cost + "); a hand that rests for seconds is lost either way");
}

void add_transform_cover_flags(CLI::App& cmd, CoverOptions& covers) {
  add_cover_flags(cmd, covers.keep_occluders, covers.moving_covers,
                  "Re-render the face over whatever covers it (a microphone, a cup, hair, a hand), moving it with the "
                  "new expression,",
                  "on frames where some patch of the face changed colour; on a talking head at 720p on 2 cores, end "
                  "to end 27-28 fps against 28-29, and 31-32 with --no-occlusion");
}

void add_lip_weight_option(CLI::App& cmd, LipCorrectionOptions& lips) {
  cmd.add_option("--lip-weight", lips.alpha,
                 "How strictly the middle of the lips is held where the speaker put it (eq. 5.4's alpha, per cm^2: "
                 "the paper's 1000 per FaceWarehouse unit^2). Higher keeps the speech's lips more exactly and lets "
                 "less of the new expression reach the mouth (1000: pinned); 0: the lips go where the expression takes "
                 "them")
      ->check(number_between(0, 1e6))
      ->capture_default_str();
}

void add_swap_texture_flags(CLI::App& cmd, SwapOptions& swap) {
  // `swap` outlives the parse: it is part of the subcommand's arguments.
  cmd.add_flag_callback(
      "--no-mirror", [&swap] { swap.mirror_source = false; },
      "Do not complete the side of the face the photo sees obliquely from its mirror image (for a face "
      "that is not left-right symmetric: a scar, a patch)");
  cmd.add_flag_callback(
      "--no-light-colour", [&swap] { swap.follow_light_colour = false; },
      "Do not tint the new face as the target light's colour changes from that of the first frames (white "
      "balance, a warmer lamp); its brightness follows the target's lighting either way");
  cmd.add_option("--residual-shading", swap.residual_shading_mm,
                 "Width (Gaussian sigma, mm on the face) of the target's shading that its lighting model leaves "
                 "unexplained (light falling off toward the chin, a broad shadow) and the new face follows; smaller "
                 "copies more of the target's own look onto the new face. 0: off")
      ->check(number_between(0, 100))
      ->capture_default_str();
  cmd.add_flag_callback(
      "--no-expression-ratio", [&swap] { swap.expression_ratio = false; },
      "Do not carry the target's own fine change of appearance since its first frames (folds and creases that "
      "come and go with its expression, kept off the target's own texture edges) onto the new face");
  cmd.add_option("--photo-detail", swap.photo_detail_gain,
                 "Gain on the photo's mid-scale detail (0.4-3 mm), where its texture holds its own folds and shadows "
                 "that land in the wrong place on another expression; 1 keeps the photo's texture as it is")
      ->check(number_between(0, 1))
      ->capture_default_str();
  add_cover_flags(cmd, swap.keep_occluders, swap.moving_covers,
                  "Paint the new face over whatever covers the target's face (a microphone, a cup, hair, a hand)",
                  "on frames where some patch of the face changed colour; on a talking head at 720p on 2 cores, "
                  "32-39 fps against 40-41");
  cmd.add_flag_callback(
      "--no-grade-match", [&swap] { swap.match_grade = false; },
      "Keep the photo's range of skin hues where the target shows a narrower one (a desaturated or sepia grade); "
      "by default the new face's hues are narrowed to the target face's spread, never widened");
}

void add_face_photo_option(CLI::App& cmd, std::string& photo) {
  cmd.add_option("--face-photo", photo,
                 "Give the synthetic face the skin of the largest face in this portrait (unshaded into the face "
                 "model's texture layout) instead of a painted one: brows, lids, lips and skin as a detector trained "
                 "on photos expects them. The output is marked as showing a real person's skin");
}

cv::Mat face_photo_texture(const FaceModel& model, const std::string& photo) {
  return photo.empty() ? cv::Mat() : face_texture_from_photo(model, photo);
}

void use_face_photo(const FaceModel& model, const std::string& photo, SynthOptions& synth) {
  if (photo.empty()) return;
  synth.face_texture = face_photo_texture(model, photo);
  synth.face_texture_source = photo;
}

}  // namespace facecap::cli
