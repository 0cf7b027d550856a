#pragma once
// The animated glTF of a capture that may cut between shots (shot_cut.hpp),
// one file per shot: each shot has its own face (identity), focal length and
// albedo, so one file animating the first shot's face through the next
// speaker's keys would show the wrong person through the wrong lens.
//
// The first shot with a face goes to the path asked for (`animation.glb`,
// `transform --gltf out.glb`); each later shot with a face to the same name
// with `_shot<N>` before the extension, N as frames.jsonl's "shot" counts
// (`animation_shot1.glb`). A video that never cuts writes the one file, as
// before.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "facecap/core/atomic_file.hpp"
#include "facecap/fit/coarse_tracker.hpp"
#include "facecap/pipeline/face_animation.hpp"

namespace facecap {

// The file of shot `shot`: `path` itself for the first shot with a face
// (`first`), else path's stem + "_shot<shot>" + its extension.
std::filesystem::path shot_file(const std::filesystem::path& path, int shot, bool first);

// A shot's animation name: `base`, with " shot <N>" after the first shot.
inline std::string shot_animation_name(const std::string& base, int shot) {
  return shot > 0 ? base + " shot " + std::to_string(shot) : base;
}

// One shot's keys, as a job hands them to its writer.
struct ShotKeys {
  int shot = 0;
  IdentityEstimate identity;  // the shot's face and focal length
  std::vector<FaceAnimationKey> keys;
};

// Removes the `<stem>_shot<N><extension>` files beside `path`, and their
// sidecars (`.json`), that are not in `written`: an earlier run's later shots
// would read as this run's. `path` itself (and its sidecar) goes too when
// `written` is empty and `remove_first_when_none`.
void remove_other_shot_files(const std::filesystem::path& path, const std::vector<std::filesystem::path>& written,
                             bool remove_first_when_none);

// Where one shot's file goes: written now under staged names, renamed to
// `file` (and its sidecar) when the job finishes (ShotAnimations::finish).
struct ShotOutput {
  std::filesystem::path file;        // its name once the job completes
  std::filesystem::path write_to;    // where to write the glTF now
  std::filesystem::path sidecar_to;  // where to write its sidecar now, if the job marks its output
};

class ShotAnimations {
 public:
  // Writes one shot's file (write_glb, and a sidecar where the job marks
  // its output as synthetic). Runs when the shot ends, while the job still
  // holds what it learnt of the shot (its albedo, the swap's appearance).
  using WriteShot = std::function<void(const ShotOutput& out, const ShotKeys& shot)>;

  // `inputs`: files a shot's path must never replace (ensure_not_an_input).
  ShotAnimations(std::filesystem::path path, WriteShot write, std::vector<std::string> inputs = {});

  // The keys of `shot`, into which the job appends (append_animation_key).
  // A shot other than the current one ends the current one first.
  std::vector<FaceAnimationKey>& keys(int shot, const IdentityEstimate& identity);

  // Writes the current shot's file if it has keys. A job whose learnt state
  // is reset before its first frame of the next shot reaches keys() (the
  // refiner's albedo, RefineStage::on_shot_end) calls this at the cut.
  void end_shot();

  // Ends the last shot, puts every shot's file in place, and removes what
  // an earlier run left under these names that this run did not write
  // (remove_other_shot_files; the first shot's file too when no shot had a
  // face). Returns the files written, first shot first. A job that fails
  // before this shows none of them.
  std::vector<std::filesystem::path> finish();

 private:
  std::filesystem::path path_;
  WriteShot write_;
  std::vector<std::string> inputs_;
  std::optional<ShotKeys> current_;
  std::vector<std::filesystem::path> written_;
  std::vector<std::filesystem::path> sidecars_to_;  // each written shot's staged sidecar
  StagedFiles staged_;
};

}  // namespace facecap
