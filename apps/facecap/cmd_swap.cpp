#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "facecap/pipeline/swap_job.hpp"

namespace facecap::cli {

namespace {

void report_swap(const SwapJobTimings& timings, const std::string& output) {
  const double n = std::max(1, timings.swapped);
  const SwapTimings& t = timings.swap;
  std::fprintf(stderr,
               "source %.0f ms | per frame swapped: lighting %.2f, appearance %.2f (first frames only), render %.2f, "
               "wrinkles %.2f, expression ratio %.2f, occlusion %.2f (its optical flow on %d of %d frames), warp %.2f, "
               "blend %.2f ms\nwrote %s and %s.json (synthetic-media marks)\n",
               timings.source_ms, timings.lighting_ms / n, t.appearance_ms / n, t.render_ms / n, t.wrinkle_ms / n,
               t.ratio_ms / n, t.occlusion_ms / n, t.flow_frames, timings.swapped, t.warp_ms / n, t.blend_ms / n,
               output.c_str(), output.c_str());
}

}  // namespace

void register_swap(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("swap",
                                 "Put the face from one portrait photo into a video, keeping the video's expression, "
                                 "pose and lighting; writes a video marked as synthetic");
  struct Args {
    std::string source, target, output;
    SwapJobOptions options;
    bool no_warp = false;
    bool photo_size = false;
    bool all_faces = false;
    std::vector<std::string> face_sources;
    AllFacesOptions all;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--source", a->source,
                  "Portrait photo whose face is put in (of several, the largest or --source-face's), or a short video "
                  "or folder of "
                  "photos of that face: its identity is then solved over --source-frames frames")
      ->required();
  cmd->add_option("--source-frames", a->options.source_frames,
                  "Frames of a source video or folder the identity is solved from (the appearance is its first)")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  add_face_option(*cmd, a->options.source_face, "--source-face",
                  "Which face of the source to use where it shows several (a group photo): largest (default), left, "
                  "right, or X,Y (pixels: the face nearest that point)");
  cmd->add_option("--target", a->target, "Video (or image folder, or cam:N) whose face is replaced")->required();
  cmd->add_option("-o,--output", a->output,
                  "Output video (.mp4, .m4v, .mov or .mkv), or for a photo target also an image (.png, .jpg, .jpeg) "
                  "marked as synthetic in its metadata; OUT.json is its synthetic-media sidecar")
      ->required();
  CLI::Option* gltf = cmd->add_option(
      "--gltf", a->options.gltf,
      "Also write the swapped performance as an animated glTF (.glb, as track --gltf): the source's face "
      "at the target's size with its harmonised texture, keyed by the target's pose and expression; "
      "marked as synthetic, with a sidecar OUT.glb.json. A target that cuts gets one per shot: "
      "OUT_shot<N>.glb after the first");
  add_matte_option(*cmd, a->options.matte, "new face");
  add_encoding_options(*cmd, a->options.encoding, "the output video (a --matte is lossless)");
  add_frame_range_options(*cmd, a->options.capture);
  CLI::Option* face = add_fit_options(*cmd, a->options.capture).face;
  CLI::Option* identity = add_identity_option(*cmd, a->options.capture.fit.known_identity);
  CLI::Option* all_faces = add_all_faces_options(
      *cmd, a->all_faces, a->all,
      "Put the source's face on every face the target shows, into the one output, each from the frame it is first "
      "found in (a face entering later is found within --search-every frames): to replace everyone in a clip, as "
      "for anonymising bystanders with a consenting person's face");
  all_faces->excludes(face)->excludes(identity)->excludes(gltf);  // each is one face's
  add_leave_faces_option(*cmd, all_faces, a->all);
  cmd->add_option("--face-source", a->face_sources,
                  "--all-faces: put another face on face K, K=PHOTO (a photo, short video or folder, as --source; its "
                  "largest face) instead of --source's; repeat for more faces")
      ->type_name("K=PHOTO")
      ->needs(all_faces)
      ->check(face_value_check());
  cmd->add_option("--appearance-frames", a->options.swap.appearance_frames,
                  "Target frames over which the appearance is harmonised, then held (counted once the target's "
                  "albedo, which its lighting is estimated against, is fixed: its first 4 frames with a face)")
      ->check(whole_number_at_least(1))
      ->capture_default_str();
  cmd->add_flag("--no-warp", a->no_warp, "Do not warp the target background to the new face outline");
  cmd->add_flag("--wrinkles", a->options.swap.wrinkles,
                "Predict the target's expression wrinkles on the new face (§6.1.2; refines the target, slower)");
  cmd->add_flag("--photo-size", a->photo_size,
                "Keep the new face at the size the photo's fit gives it (default: the target face's size; a "
                "single photo does not fix a face's absolute size)");
  add_swap_texture_flags(*cmd, a->options.swap);
  cmd->callback([a, &global] {
    a->options.swap.warp_background = !a->no_warp;
    a->options.swap.match_target_size = !a->photo_size;
    a->options.capture.quiet = global.quiet;
    std::map<int, std::string>& sources = a->options.face_sources;
    for (const std::string& text : a->face_sources) {
      const auto [face, photo] = parse_face_value(text);
      if (!sources.emplace(face, photo).second)
        throw CLI::ValidationError("--face-source", "face " + std::to_string(face) + " is given two sources");
    }
    const FaceModel model = load_model(global);
    if (a->all_faces) {
      const AllFacesSwapSummary s = run_swap_all_faces(model, a->source, a->target, a->output, a->options, a->all);
      report_edited_faces(
          s.target, a->all, "swapped", [&s](int k) { return s.swapped[k]; },
          [&sources](int k) {
            const auto own = sources.find(k);
            return own != sources.end() ? "the face from " + own->second : std::string();
          });
      report_swap(s.timings, a->output);
      report_uncaptured_faces(s.target, "left as they are");
      std::vector<int> named;
      for (const auto& [face, photo] : sources) named.push_back(face);
      report_unfound_faces(named, s.target, "--face-source");
      return;
    }
    const SwapSummary s = run_swap(model, a->source, a->target, a->output, a->options);
    std::fprintf(stderr, "frames %d, swapped %d, lost %d\n", s.target.frames, s.timings.swapped, s.target.lost);
    report_swap(s.timings, a->output);
    if (const std::string note = unreadable_frames_note(s.target, a->target); !note.empty())
      std::fprintf(stderr, "facecap: %s (black in the output)\n", note.c_str());
    report_damaged_input(s.target.damage, a->target);
    for (const std::filesystem::path& file : s.animation_files)
      std::fprintf(stderr, "wrote %s and %s.json\n", file.c_str(), file.c_str());
    if (!a->options.matte.empty())
      std::fprintf(stderr, "wrote %s and %s.json (the matte)\n", a->options.matte.c_str(), a->options.matte.c_str());
  });
}

}  // namespace facecap::cli
