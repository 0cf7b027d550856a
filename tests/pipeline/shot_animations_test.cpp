#include "facecap/pipeline/shot_animations.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {
namespace {

namespace fs = std::filesystem;

void touch(const fs::path& p) { std::ofstream(p) << "x"; }

FaceAnimationKey key(double time) {
  FaceAnimationKey k;
  k.time = time;
  return k;
}

TEST(ShotAnimations, OneFilePerShotWithKeysTheFirstUnderThePlainName) {
  TempDir dir;
  const fs::path path = dir.path() / "out.glb";
  // An earlier run's later shots, and files that only look like them.
  for (const char* name :
       {"out_shot3.glb", "out_shot3.glb.json", "out_shot9.glb", "out_shotx.glb", "other_shot3.glb", "out_shot3.png"})
    touch(dir.path() / name);
  std::vector<std::pair<fs::path, ShotKeys>> written;
  ShotAnimations animations(path,
                            [&](const fs::path& file, const ShotKeys& shot) { written.emplace_back(file, shot); });
  IdentityEstimate first, second;
  first.focal = 1500;
  second.focal = 1700;
  animations.keys(1, first).push_back(key(0.0));  // shot 0 had no face: shot 1 is the first with one
  animations.keys(1, first).push_back(key(0.1));
  animations.keys(2, second);  // a shot whose frames were all lost: no keys, no file
  animations.keys(3, second).push_back(key(1.0));
  animations.end_shot();
  animations.end_shot();  // harmless twice (a cut's hook, then the next shot's first frame)
  animations.keys(5, second).push_back(key(2.0));
  const std::vector<fs::path> files = animations.finish();

  ASSERT_EQ(written.size(), 3u);
  EXPECT_EQ(written[0].first, path);
  EXPECT_EQ(written[0].second.shot, 1);
  EXPECT_EQ(written[0].second.keys.size(), 2u);
  EXPECT_EQ(written[0].second.identity.focal, 1500);
  EXPECT_EQ(written[1].first, dir.path() / "out_shot3.glb");
  EXPECT_EQ(written[1].second.identity.focal, 1700);
  EXPECT_EQ(written[2].first, dir.path() / "out_shot5.glb");
  EXPECT_EQ(files, (std::vector<fs::path>{path, dir.path() / "out_shot3.glb", dir.path() / "out_shot5.glb"}));
  // The fake writer wrote nothing: out_shot3.glb is the earlier run's, but
  // this run names it, so it stays; shot 9 and its kind go, the look-alikes stay.
  EXPECT_TRUE(fs::exists(dir.path() / "out_shot3.glb"));
  EXPECT_FALSE(fs::exists(dir.path() / "out_shot9.glb"));
  for (const char* name : {"out_shotx.glb", "other_shot3.glb", "out_shot3.png"})
    EXPECT_TRUE(fs::exists(dir.path() / name)) << name;
}

TEST(ShotAnimations, NoShotWithAFaceRemovesAnEarlierRunsFiles) {
  TempDir dir;
  const fs::path path = dir.path() / "animation.glb";
  for (const char* name : {"animation.glb", "animation.glb.json", "animation_shot1.glb", "animation_shot1.glb.json"})
    touch(dir.path() / name);
  int writes = 0;
  ShotAnimations animations(path, [&](const fs::path&, const ShotKeys&) { ++writes; });
  animations.keys(0, IdentityEstimate{});
  EXPECT_TRUE(animations.finish().empty());
  EXPECT_EQ(writes, 0);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(ShotAnimations, AShotsFileNeverReplacesAnInput) {
  TempDir dir;
  const fs::path input = dir.path() / "clip_shot1.glb";
  touch(input);
  ShotAnimations animations(dir.path() / "clip.glb", [](const fs::path&, const ShotKeys&) {}, {input.string()});
  animations.keys(0, IdentityEstimate{}).push_back(key(0));
  animations.keys(1, IdentityEstimate{}).push_back(key(1));
  EXPECT_THROW(animations.finish(), Error);
}

}  // namespace
}  // namespace facecap
