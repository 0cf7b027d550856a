#include "facecap/pipeline/shot_animations.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

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
  ShotAnimations animations(path, [&](const ShotOutput& out, const ShotKeys& shot) {
    written.emplace_back(out.file, shot);
    if (shot.shot == 3) std::ofstream(out.write_to) << "this run's shot 3";  // the others write nothing
  });
  IdentityEstimate first, second;
  first.focal = 1500;
  second.focal = 1700;
  animations.keys(1, first).push_back(key(0.0));  // shot 0 had no face: shot 1 is the first with one
  animations.keys(1, first).push_back(key(0.1));
  animations.keys(2, second);  // a shot whose frames were all lost: no keys, no file
  animations.keys(3, second).push_back(key(1.0));
  animations.end_shot();
  animations.end_shot();  // harmless twice (a cut's hook, then the next shot's first frame)
  // Written, but not in place until the job completes.
  EXPECT_EQ(test::read_file(dir.path() / "out_shot3.glb"), "x");
  animations.keys(5, second).push_back(key(2.0));
  const std::vector<fs::path> files = animations.finish();
  EXPECT_EQ(test::read_file(dir.path() / "out_shot3.glb"), "this run's shot 3");

  ASSERT_EQ(written.size(), 3u);
  EXPECT_EQ(written[0].first, path);
  EXPECT_EQ(written[0].second.shot, 1);
  EXPECT_EQ(written[0].second.keys.size(), 2u);
  EXPECT_EQ(written[0].second.identity.focal, 1500);
  EXPECT_EQ(written[1].first, dir.path() / "out_shot3.glb");
  EXPECT_EQ(written[1].second.identity.focal, 1700);
  EXPECT_EQ(written[2].first, dir.path() / "out_shot5.glb");
  EXPECT_EQ(files, (std::vector<fs::path>{path, dir.path() / "out_shot3.glb", dir.path() / "out_shot5.glb"}));
  // Shot 3's file is this run's, and the earlier run's sidecar of that name
  // goes with what it said (this writer writes none); shot 9's goes; the
  // look-alikes stay.
  EXPECT_TRUE(fs::exists(dir.path() / "out_shot3.glb"));
  EXPECT_FALSE(fs::exists(dir.path() / "out_shot3.glb.json"));
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
  ShotAnimations animations(path, [&](const ShotOutput&, const ShotKeys&) { ++writes; });
  animations.keys(0, IdentityEstimate{});
  EXPECT_TRUE(animations.finish().empty());
  EXPECT_EQ(writes, 0);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(ShotAnimations, AShotsFileNeverReplacesAnInput) {
  TempDir dir;
  const fs::path input = dir.path() / "clip_shot1.glb";
  touch(input);
  ShotAnimations animations(dir.path() / "clip.glb", [](const ShotOutput&, const ShotKeys&) {}, {input.string()});
  animations.keys(0, IdentityEstimate{}).push_back(key(0));
  animations.keys(1, IdentityEstimate{}).push_back(key(1));
  EXPECT_THROW(animations.finish(), Error);
}

// A job that fails after a cut (the animations never finish) shows none of
// its shots' files, and leaves an earlier run's in place.
TEST(ShotAnimations, AJobThatFailsShowsNoShotsFile) {
  TempDir dir;
  const fs::path path = dir.path() / "out.glb";
  std::ofstream(dir.path() / "out_shot1.glb") << "an earlier run's";
  {
    ShotAnimations animations(path, [&](const ShotOutput& out, const ShotKeys&) {
      std::ofstream(out.write_to) << "this run's";
      std::ofstream(out.sidecar_to) << "{}";
    });
    animations.keys(0, IdentityEstimate{}).push_back(key(0));
    animations.keys(1, IdentityEstimate{}).push_back(key(1));
    animations.end_shot();
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(test::read_file(dir.path() / "out_shot1.glb"), "an earlier run's");
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace facecap
