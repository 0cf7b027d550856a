#include "facecap/pipeline/shot_animations.hpp"

#include <algorithm>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/io/synthetic_mark.hpp"

namespace facecap {

namespace fs = std::filesystem;

fs::path shot_file(const fs::path& path, int shot, bool first) {
  if (first) return path;
  return path.parent_path() / (path.stem().string() + "_shot" + std::to_string(shot) + path.extension().string());
}

ShotAnimations::ShotAnimations(fs::path path, WriteShot write, std::vector<std::string> inputs)
    : path_(std::move(path)), write_(std::move(write)), inputs_(std::move(inputs)) {}

std::vector<FaceAnimationKey>& ShotAnimations::keys(int shot, const IdentityEstimate& identity) {
  if (current_ && current_->shot != shot) end_shot();
  if (!current_) current_ = ShotKeys{shot, identity, {}};
  return current_->keys;
}

void ShotAnimations::end_shot() {
  if (!current_) return;
  const ShotKeys shot = std::move(*current_);
  current_.reset();
  if (shot.keys.empty()) return;
  const fs::path file = shot_file(path_, shot.shot, written_.empty());
  for (const std::string& input : inputs_) ensure_not_an_input(file, {input});
  const fs::path write_to = staged_.stage(file);
  const fs::path sidecar_to = staged_.stage(sidecar_path(file));
  write_({file, write_to, sidecar_to}, shot);
  written_.push_back(file);
  sidecars_to_.push_back(sidecar_to);
}

std::vector<fs::path> ShotAnimations::finish() {
  end_shot();
  // A shot whose writer marks nothing keeps no sidecar an earlier run left.
  std::vector<fs::path> unmarked;
  std::error_code ec;
  for (size_t k = 0; k < written_.size(); ++k)
    if (!fs::exists(sidecars_to_[k], ec)) unmarked.push_back(sidecar_path(written_[k]));
  staged_.commit();
  for (const fs::path& p : unmarked) fs::remove(p, ec);
  remove_other_shot_files(path_, written_, /*remove_first_when_none=*/true);
  return written_;
}

void remove_other_shot_files(const fs::path& path, const std::vector<fs::path>& written, bool remove_first_when_none) {
  std::error_code ec;
  if (written.empty() && remove_first_when_none) {
    fs::remove(path, ec);
    fs::remove(sidecar_path(path), ec);
  }
  // Earlier runs' later shots: <stem>_shot<digits><extension>, and sidecars.
  const std::string prefix = path.stem().string() + "_shot";
  const std::string extension = path.extension().string();
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::string name = entry.path().filename().string();
    if (name.ends_with(extension + ".json")) name.resize(name.size() - 5);  // a sidecar
    if (!numbered_name_digits(name, prefix, extension)) continue;
    const bool ours =
        std::any_of(written.begin(), written.end(), [&](const fs::path& w) { return w.filename().string() == name; });
    if (!ours) stale.push_back(entry.path());
  }
  for (const fs::path& p : stale) fs::remove(p, ec);
}

}  // namespace facecap
