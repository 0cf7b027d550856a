#pragma once
// The subcommands of the facecap program. Each registers its options on the
// CLI and maps them onto the library's option structs; none holds an algorithm.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "facecap/expr/emotions.hpp"
#include "facecap/io/input_damage.hpp"
#include "facecap/io/video_encoding.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/refine/compute_device.hpp"
#include "facecap/swap/face_swapper.hpp"

namespace facecap {
struct FacePick;
struct AllFacesOptions;
struct AllFacesSummary;
struct SynthOptions;
struct CaptureOptions;
struct CoverOptions;
struct LipCorrectionOptions;
}  // namespace facecap

namespace facecap::cli {

struct GlobalOptions {
  std::string model_dir;  // empty: default_model_dir()
  bool quiet = false;
};

// Loads the face model (through its cache), with a one-line note on stderr.
FaceModel load_model(const GlobalOptions& global);
// Prints a JSON object on stdout.
void print_json(const nlohmann::json& j);
// Parses "WxH"; throws facecap::Error naming --size otherwise.
void parse_size(const std::string& s, int& width, int& height);
// An expression named on the command line (parse_emotion's names); throws
// facecap::Error naming `option` and the choices otherwise.
Emotion emotion_argument(const std::string& option, const std::string& value);
// --crf and --x264-preset: x264's settings (VideoEncoding) for `what`, the
// videos a command writes; with `needs`, only beside that option.
void add_encoding_options(CLI::App& cmd, VideoEncoding& encoding, const std::string& what,
                          CLI::Option* needs = nullptr);
// --init-frames: the frames the identity and focal length are solved from
// (CoarseFitOptions::init_frames).
void add_init_frames_option(CLI::App& cmd, int& init_frames);
// --smooth-frames (CoarseFitOptions::smooth_frames).
CLI::Option* add_smooth_frames_option(CLI::App& cmd, int& smooth_frames);
// Refuses a value that is not a whole number of at least `least`, naming it
// (CLI11's own range checks print the type's whole range).
CLI::Validator whole_number_at_least(int least);
// Refuses a value that is not a number from `least` to `most` (NaN among
// them, which CLI11's Range lets through).
CLI::Validator number_between(double least, double most);
// Refuses an expression that is not one of parse_emotion's names, naming
// the choices.
CLI::Validator emotion_value();
// Refuses a synthetic frame size that is not WxH from 64 to 8192 a side
// (SynthOptions::check's range), naming it.
CLI::Validator synthetic_frame_size();
// --start SECONDS: where track, transform, swap and bench track start reading
// a video (CaptureOptions::start_seconds).
void add_start_option(CLI::App& cmd, double& start_seconds);
// --no-shot-cuts: one identity and focal length for the whole input (CaptureOptions::shot_cuts).
void add_shot_cuts_option(CLI::App& cmd, bool& shot_cuts);
// --max-frames and --start: which frames of the input a command reads.
void add_frame_range_options(CLI::App& cmd, CaptureOptions& capture);
// How a capture is fitted and whose face it follows, as every command that
// captures asks it: --init-frames, --smooth-frames, --no-shot-cuts and --face.
// Returns the two options others exclude or need.
struct FitCliOptions {
  CLI::Option* smooth_frames;
  CLI::Option* face;
};
FitCliOptions add_fit_options(CLI::App& cmd, CaptureOptions& capture);
// --units AU12=3,AU4=0: a FACS edit (action_units.hpp), checked when given
// (parse_action_unit_targets names what is wrong). Returns the option.
CLI::Option* add_action_units_option(CLI::App& cmd, std::string& units, const std::string& help);
// --face largest|left|right|X,Y: which face to follow where several are in
// view (FaceTrackerOptions::pick); `name` and `help` for another input's
// (swap's --source-face).
CLI::Option* add_face_option(CLI::App& cmd, FacePick& pick, const std::string& name = "--face",
                             const std::string& help = "");
// --all-faces (help: what it does for this command), with --max-faces and
// --search-every (AllFacesOptions), which need it. Returns the flag.
CLI::Option* add_all_faces_options(CLI::App& cmd, bool& all_faces, AllFacesOptions& all, const std::string& help);
// --leave-faces K,K...: for transform and swap --all-faces, the faces (by
// the index track --all-faces gives them, in faces.png) left as they are
// (AllFacesOptions::unedited). Needs `all_faces`.
void add_leave_faces_option(CLI::App& cmd, CLI::Option* all_faces, AllFacesOptions& all);
// One value of a per-face option of --all-faces, "K=VALUE" (--face-to
// 1=sadness, --face-source 1=photo.jpg): the face's index (as --leave-faces
// numbers faces) and the value. Throws facecap::Error ("must be K=VALUE ...")
// when the text is not that.
std::pair<int, std::string> parse_face_value(const std::string& text);
// A CLI11 check of such an option's values (a usage error, exit 2, named by
// CLI11): the K=VALUE form, and `value` (which throws facecap::Error with
// what is wrong) on the value.
CLI::Validator face_value_check(std::function<void(const std::string& value)> value = nullptr);
// One line on stderr per face of an --all-faces edit, "face K (from frame
// F): frames N, <verb> E, lost L", with in brackets --leave-faces for a face
// left as it is, or `own(K)` for one with a choice of its own (per-face
// options; empty: none). `edited(K)`: the frames the edit changed.
void report_edited_faces(const AllFacesSummary& all, const AllFacesOptions& options, const char* verb,
                         const std::function<int(int face)>& edited, const std::function<std::string(int face)>& own);
// One line on stderr for each face a per-face option named but the input
// did not show: "facecap: face K (<option>) was not found".
void report_unfound_faces(const std::vector<int>& named, const AllFacesSummary& all, const char* option);
// One line on stderr where --all-faces left faces out (--max-faces): "up to
// N more face(s) at once were <what>".
void report_uncaptured_faces(const AllFacesSummary& all, const char* what);
// A line on stderr for each kind of damage `what` had (input_damage_notes):
// frames decoded with damage, packets the decoder refused, an early end;
// nothing where it had none.
void report_damaged_input(const InputDamage& damage, const std::string& what);
// --matte FILE: the edit's matte (SwapJobOptions / TransformJobOptions::matte);
// `what`: what the matte shows ("new face").
void add_matte_option(CLI::App& cmd, std::filesystem::path& matte, const std::string& what);
// --identity FILE: hold the identity of an earlier capture's identity.json
// (CoarseFitOptions::known_identity), read when the option is parsed.
CLI::Option* add_identity_option(CLI::App& cmd, std::optional<Eigen::VectorXd>& identity);
// --no-mirror, --no-light-colour, --residual-shading and --photo-detail:
// how the swap completes, tints, shades and filters the photo's texture;
// --no-occlusion: whether it leaves what covers the target's face in front
// (SwapOptions), for `swap` and `eval swap` alike.
void add_swap_texture_flags(CLI::App& cmd, SwapOptions& swap);
// --no-occlusion and --no-moving-covers: whether an edit leaves what covers
// the face in front of it, and finds a hand of the skin's colour by its
// motion. `paint_over`: what the edit does without it; `cost`: the motion
// test's cost in frames per second.
void add_cover_flags(CLI::App& cmd, bool& keep_occluders, bool& moving_covers, const std::string& paint_over,
                     const std::string& cost);
// The same for transform, bench transform and eval transform (TransformJobOptions::covers).
void add_transform_cover_flags(CLI::App& cmd, CoverOptions& covers);
// --lip-weight A: eq. 5.4's alpha, how strictly the key lip vertices are held
// where the speaker put them (LipCorrectionOptions), for transform and eval transform.
void add_lip_weight_option(CLI::App& cmd, LipCorrectionOptions& lips);
// --device cpu|cuda: where the refinement's sampling, albedo and displacement solves run (default:
// cuda when this build has it and a GPU answers, else cpu).
void add_device_option(CLI::App& cmd, ComputeDevice& device);
// --face-photo PHOTO: give the synthetic face that portrait's skin rather
// than a painted one (SynthOptions::face_texture).
void add_face_photo_option(CLI::App& cmd, std::string& photo);
// --face-photo's texture (face_texture_from_photo); empty when `photo` is.
cv::Mat face_photo_texture(const FaceModel& model, const std::string& photo);
// Puts it and its source into `synth` (nothing when `photo` is empty).
void use_face_photo(const FaceModel& model, const std::string& photo, SynthOptions& synth);

void register_probe(CLI::App& app, GlobalOptions& global);
void register_model(CLI::App& app, GlobalOptions& global);
void register_synth(CLI::App& app, GlobalOptions& global);
void register_eval(CLI::App& app, GlobalOptions& global);
void register_demo(CLI::App& app, GlobalOptions& global);
void register_track(CLI::App& app, GlobalOptions& global);
void register_bench(CLI::App& app, GlobalOptions& global);
void register_transform(CLI::App& app, GlobalOptions& global);
void register_swap(CLI::App& app, GlobalOptions& global);

}  // namespace facecap::cli
