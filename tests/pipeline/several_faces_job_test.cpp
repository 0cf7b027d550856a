// Capture and both edits of footage with more than one face: a shot cut to
// another speaker, and --all-faces, where each face is captured or edited as
// its own run would, into its own folder or the one output.
#include "facecap/pipeline/track_job.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "app/command.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/livelink_face.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/pipeline/swap_job.hpp"
#include "facecap/pipeline/track_each_face.hpp"
#include "facecap/pipeline/transform_job.hpp"
#include "io/glb_reader.hpp"
#include "io/livelink_receiver.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines(const fs::path& p) { return test::read_lines(p); }

// Writes `out`, a silent H.264 test clip of `inputs`, each read as 25 fps
// (frames kept, not resampled), through the ffmpeg filter graph `graph` (its
// output is [v]), and returns its path; throws with ffmpeg's words if it fails.
fs::path compose_clip(const std::vector<fs::path>& inputs, const std::string& graph, const fs::path& out) {
  std::string command = "ffmpeg -nostdin -hide_banner -loglevel error -y";
  for (const fs::path& in : inputs) command += " -r 25 -i " + in.string();
  const test::CommandResult made =
      test::run_command(command + " -filter_complex \"" + graph +
                        "\" -map \"[v]\" -an -c:v libx264 -preset ultrafast -crf 16 " + out.string() + " 2>&1");
  if (made.code != 0) throw std::runtime_error("ffmpeg could not compose " + out.string() + ": " + made.out);
  return out;
}

// Two people side by side (1280x360, 56 frames) after 8 black frames (a
// fade-in): `left` on the left from frame 8, `right` sliding in from the
// right edge over frames 20-28.
fs::path two_people_clip(const fs::path& left, const fs::path& right, const fs::path& out) {
  return compose_clip(
      {left, right},
      "[0:v]trim=end_frame=48,scale=640:360,pad=1280:360:0:0,setsar=1[a];[1:v]trim=end_frame=48,scale=480:360,pad=640:"
      "360:80:0,setsar=1[b];[a][b]overlay=x='640+max(0\\,(20-n)*80)':y=0,tpad=start=8:color=black[v]",
      out);
}

// Every frame of `video`, decoded.
std::vector<cv::Mat> decoded_frames(const fs::path& video) {
  std::vector<cv::Mat> frames;
  auto source = open_input(video.string());
  Frame f;
  while (source->read(f)) frames.push_back(f.image.clone());
  return frames;
}

// A grey picture with no face in it, written into `dir`.
fs::path faceless_image(const fs::path& dir) {
  const fs::path grey = dir / "grey.png";
  facecap::write_image(grey.string(), cv::Mat(200, 300, CV_8UC3, cv::Scalar(128, 128, 128)));
  return grey;
}

// An --all-faces edit of two_people_clip (`both`, its frames as written)
// against each face's own run (`left_alone`, `right_alone`, from where the
// face was found): the black frames are the input's; then each half is, to
// the pixel, its face's own run, and changed from the input; the right half
// is the input's before its face is found (at `entered`).
void expect_each_half_as_its_own_run(const std::map<int, cv::Mat>& both, const std::map<int, cv::Mat>& left_alone,
                                     const std::map<int, cv::Mat>& right_alone, const std::vector<cv::Mat>& input,
                                     int entered) {
  const cv::Rect left_half(0, 0, 640, 360), right_half(640, 0, 640, 360);
  for (const auto& [i, b] : both) {
    if (i < 8) {
      EXPECT_EQ(cv::norm(b, input[i], cv::NORM_INF), 0.0) << i;  // no face: the input's frame
      continue;
    }
    EXPECT_EQ(cv::norm(b(left_half), left_alone.at(i)(left_half), cv::NORM_INF), 0.0) << i;
    EXPECT_GT(cv::norm(b(left_half), input[i](left_half), cv::NORM_L1), 0.0) << i;  // edited
    if (i < entered) {
      EXPECT_EQ(cv::norm(b(right_half), input[i](right_half), cv::NORM_INF), 0.0) << i;
    } else {
      EXPECT_EQ(cv::norm(b(right_half), right_alone.at(i)(right_half), cv::NORM_INF), 0.0) << i;
      EXPECT_GT(cv::norm(b(right_half), input[i](right_half), cv::NORM_L1), 0.0) << i;
    }
  }
}

}  // namespace

// An edit that cuts from one speaker to another (address_720p_a, then
// talking_webcam2 scaled into the same 1280x720 frame): the cut starts a
// second shot, whose identity and focal length are solved from its own
// frames. It comes out as the second clip's own (solved from it alone) to
// 0.24 in identity weights, where the two people lie 4.2 apart; with one
// identity for the whole video, the second speaker is fitted with the first
// one's face.
TEST(TrackJob, AShotCutToAnotherSpeakerSolvesTheirOwnIdentity) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(first, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(second, "talking_webcam2_400x300.mp4");
  TempDir dir;
  // 40 frames of each, both read as 25 fps (-r before -i: frames kept, not resampled).
  const std::string scaled = "scale=960:720,pad=1280:720:160:0,setsar=1";
  auto make = [&](const std::string& name, const std::vector<fs::path>& inputs, const std::string& graph) {
    return compose_clip(inputs, graph, dir.path() / name);
  };
  const fs::path joined =
      make("joined.mp4", {first, second},
           "[0:v]trim=end_frame=40,setsar=1[a];[1:v]trim=end_frame=40," + scaled + "[b];[a][b]concat=n=2:v=1:a=0[v]");
  const fs::path alone = make("alone.mp4", {second}, "[0:v]trim=end_frame=40," + scaled + "[v]");
  TrackOptions o;
  o.capture.quiet = true;
  auto identity_of = [](const fs::path& run_dir) {
    std::ifstream in(run_dir / "identity.json");
    return nlohmann::json::parse(in);
  };
  auto distance = [](const nlohmann::json& a, const nlohmann::json& b) {
    const auto x = a.get<std::vector<double>>(), y = b.get<std::vector<double>>();
    double d = 0;
    for (size_t i = 0; i < x.size(); ++i) d += (x[i] - y[i]) * (x[i] - y[i]);
    return std::sqrt(d);
  };
  run_track(*model, alone.string(), dir.path() / "alone", o);
  const nlohmann::json own = identity_of(dir.path() / "alone")["identity_weights"];

  // With its glTF and albedo, which are per shot too; an earlier run's
  // later shot in that folder is not this run's.
  TrackOptions with_files = o;
  with_files.gltf = true;
  with_files.refine = true;
  with_files.point_cache = true;
  const fs::path jd = dir.path() / "joined";
  fs::create_directories(jd);
  for (const char* name : {"animation_shot4.glb", "albedo_shot4.png", "face_shot4.pc2", "face_shot4.mtl"})
    std::ofstream(jd / name) << "earlier run";
  const TrackSummary s = run_track(*model, joined.string(), jd, with_files);
  EXPECT_EQ(s.capture.cuts, 1);
  ASSERT_EQ(s.capture.shots.size(), 2u);
  EXPECT_EQ(s.capture.shots[1].first_frame, 40);
  EXPECT_EQ(s.capture.lost, 0);
  const nlohmann::json id = identity_of(dir.path() / "joined");
  ASSERT_EQ(id["shots"].size(), 2u);
  EXPECT_EQ(id["shots"][1]["first_frame"], 40);
  EXPECT_EQ(id["identity_weights"], id["shots"][0]["identity_weights"]);  // the top level: the first shot
  EXPECT_LT(distance(id["shots"][1]["identity_weights"], own), 1.0);
  EXPECT_GT(distance(id["shots"][0]["identity_weights"], own), 2.0);
  const auto rows = lines(dir.path() / "joined" / "frames.jsonl");
  ASSERT_EQ(rows.size(), 80u);
  EXPECT_EQ(nlohmann::json::parse(rows[39])["shot"], 0);
  EXPECT_EQ(nlohmann::json::parse(rows[40])["shot"], 1);
  const auto csv = lines(jd / "frames.csv");
  ASSERT_EQ(csv.size(), 81u);
  EXPECT_TRUE(csv[40].ends_with(",0")) << csv[40];  // frame 39
  EXPECT_TRUE(csv[41].ends_with(",1")) << csv[41];  // frame 40

  // One point cache per shot, each from its shot's first frame, of its own
  // refined level.
  ASSERT_EQ(s.point_cache_files, (std::vector<fs::path>{jd / "face.pc2", jd / "face_rest.obj", jd / "face_shot1.pc2",
                                                        jd / "face_rest_shot1.obj"}));
  EXPECT_FALSE(fs::exists(jd / "face_shot4.pc2"));
  for (int shot = 0; shot < 2; ++shot) {
    const std::string cache = test::read_file(s.point_cache_files[2 * size_t(shot)]);
    ASSERT_GE(cache.size(), 32u);
    int32_t points = 0, samples = 0;
    float start = -1;
    std::memcpy(&points, cache.data() + 16, 4);
    std::memcpy(&start, cache.data() + 20, 4);
    std::memcpy(&samples, cache.data() + 28, 4);
    EXPECT_EQ(start, float(40 * shot)) << shot;
    EXPECT_EQ(samples, 40) << shot;
    EXPECT_EQ(cache.size(), 32 + size_t(points) * size_t(samples) * 12) << shot;
    const auto rest = lines(s.point_cache_files[2 * size_t(shot) + 1]);
    EXPECT_EQ(std::count_if(rest.begin(), rest.end(), [](const std::string& l) { return l.rfind("v ", 0) == 0; }),
              points)
        << shot;
    // Textured with its own shot's albedo.
    const std::string library = shot == 0 ? "face.mtl" : "face_shot1.mtl";
    EXPECT_NE(std::find(rest.begin(), rest.end(), "mtllib " + library), rest.end()) << shot;
    const auto material = lines(jd / library);
    EXPECT_NE(std::find(material.begin(), material.end(),
                        std::string("map_Kd ") + (shot == 0 ? "albedo.png" : "albedo_shot1.png")),
              material.end())
        << shot;
  }
  EXPECT_FALSE(fs::exists(jd / "face_shot4.mtl"));

  // One glTF per shot: its own face, keys, camera and albedo.
  ASSERT_EQ(s.animation_files, (std::vector<fs::path>{jd / "animation.glb", jd / "animation_shot1.glb"}));
  EXPECT_FALSE(fs::exists(jd / "animation_shot4.glb"));
  EXPECT_FALSE(fs::exists(jd / "albedo_shot4.png"));
  std::vector<std::vector<float>> rest_shapes;
  for (int shot = 0; shot < 2; ++shot) {
    const test::Glb g = test::Glb::read(s.animation_files[shot]);
    const std::vector<float> times = g.floats(g.doc["animations"][0]["samplers"][0]["input"]);
    ASSERT_EQ(times.size(), 40u) << shot;
    EXPECT_NEAR(times.front(), shot * 40 / 25.0, 1e-4) << shot;  // the video's own times
    EXPECT_NEAR(times.back(), (shot * 40 + 39) / 25.0, 1e-4) << shot;
    const double yfov = g.doc["cameras"][0]["perspective"]["yfov"];
    EXPECT_NEAR(360.0 / std::tan(yfov / 2), double(id["shots"][shot]["focal_px"]), 0.01) << shot;
    const fs::path albedo = jd / (shot == 0 ? "albedo.png" : "albedo_shot1.png");
    const cv::Mat texture = facecap::read_image(albedo.string());
    ASSERT_FALSE(texture.empty()) << albedo;
    EXPECT_GT(cv::mean(texture)[2], 20.0) << albedo;  // skin, not the restarted refiner's nothing
    const auto& view = g.doc["bufferViews"][int(g.doc["images"][0]["bufferView"])];
    EXPECT_EQ(size_t(view["byteLength"]), fs::file_size(albedo)) << shot;
    rest_shapes.push_back(g.floats(g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]));
  }
  // The first shot's albedo is the one that shot's frames alone give (baked
  // before the refiner starts again for the next shot).
  TrackOptions first_only = with_files;
  first_only.gltf = false;
  first_only.capture.max_frames = 40;
  run_track(*model, joined.string(), dir.path() / "first40", first_only);
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_TRUE(bytes(jd / "albedo.png") == bytes(dir.path() / "first40" / "albedo.png"));
  ASSERT_EQ(rest_shapes[0].size(), rest_shapes[1].size());
  float largest = 0;  // metres
  for (size_t i = 0; i < rest_shapes[0].size(); ++i)
    largest = std::max(largest, std::abs(rest_shapes[0][i] - rest_shapes[1][i]));
  EXPECT_GT(largest, 0.003f);  // two people's faces

  // transform's smoothing window (2k + 1 = 3 frames) stops at the cut: the
  // first shot's last frame is smoothed as at the end of the input, the same
  // as a run of those 40 frames alone (it took in the second speaker's first
  // frame before).
  TransformJobOptions to;
  to.capture.quiet = true;
  to.description = "test";
  to.gltf = dir.path() / "whole.glb";
  const TransformSummary whole = run_transform(*model, joined.string(), dir.path() / "whole.mp4", to);
  // Its glTF is per shot as track's, each file marked as synthetic.
  ASSERT_EQ(whole.animation_files, (std::vector<fs::path>{dir.path() / "whole.glb", dir.path() / "whole_shot1.glb"}));
  for (const fs::path& file : whole.animation_files) {
    EXPECT_TRUE(fs::exists(file.string() + ".json")) << file;
    const test::Glb g = test::Glb::read(file);
    EXPECT_EQ(g.floats(g.doc["animations"][0]["samplers"][0]["input"]).size(), 40u) << file;
  }
  to.gltf.clear();

  // So is swap's: the source's face placed and textured for each shot, seen
  // through that shot's camera.
  FACECAP_REQUIRE_DATA(photo, "portrait_biden.jpg");
  SwapJobOptions so;
  so.capture.quiet = true;
  so.gltf = dir.path() / "swap.glb";
  const SwapSummary swapped = run_swap(*model, photo.string(), joined.string(), dir.path() / "swap.mp4", so);
  ASSERT_EQ(swapped.animation_files, (std::vector<fs::path>{dir.path() / "swap.glb", dir.path() / "swap_shot1.glb"}));
  for (int shot = 0; shot < 2; ++shot) {
    const fs::path& file = swapped.animation_files[shot];
    EXPECT_TRUE(fs::exists(file.string() + ".json")) << file;
    const test::Glb g = test::Glb::read(file);
    EXPECT_EQ(g.floats(g.doc["animations"][0]["samplers"][0]["input"]).size(), 40u) << file;
    const double yfov = g.doc["cameras"][0]["perspective"]["yfov"];
    EXPECT_NEAR(360.0 / std::tan(yfov / 2), swapped.target.shots[shot].identity.focal, 0.01) << file;
  }

  to.capture.max_frames = 40;
  const TransformSummary first_shot = run_transform(*model, joined.string(), dir.path() / "first.mp4", to);
  ASSERT_EQ(whole.frames.size(), 80u);
  ASSERT_EQ(first_shot.frames.size(), 40u);
  ASSERT_TRUE(whole.frames[39].valid && first_shot.frames[39].valid);
  EXPECT_LT((whole.frames[39].smoothed - first_shot.frames[39].smoothed).cwiseAbs().maxCoeff(), 1e-5);

  // One identity for the whole video (--no-shot-cuts): the first speaker's.
  o.capture.shot_cuts = false;
  const TrackSummary one = run_track(*model, joined.string(), dir.path() / "one", o);
  EXPECT_EQ(one.capture.cuts, 0);
  EXPECT_FALSE(identity_of(dir.path() / "one").contains("shots"));
  EXPECT_GT(distance(identity_of(dir.path() / "one")["identity_weights"], own), 2.0);
}

// --all-faces: two faces side by side after 8 black frames, the right one
// sliding in 12 frames after the left, each captured into its own folder from
// the frame it is found in, left to right, on one pass; an earlier run's
// third face's folder goes.
TEST(TrackJob, AllFacesCapturesEachFaceIntoItsOwnFolder) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(left, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(right, "talking_webcam2_400x300.mp4");
  TempDir dir;
  const fs::path two = two_people_clip(left, right, dir.path() / "two.mp4");
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "face_2");
  std::ofstream(out / "face_2" / "frames.csv") << "an earlier run's\n";
  fs::create_directories(out / "face_notes");
  TrackOptions o;
  o.capture.quiet = true;
  // --livelink-udp: each face streams as a subject of its own.
  const test::UdpReceiver receiver;
  TrackOptions streamed = o;
  streamed.livelink_stream.emplace();
  streamed.livelink_stream->target = {"127.0.0.1", receiver.port()};
  streamed.livelink_stream->paced = false;
  const EachFaceSummary each = run_track_each_face(*model, two.string(), out, streamed);
  ASSERT_EQ(each.faces.size(), 2u);
  ASSERT_EQ(each.runs.size(), 2u);
  EXPECT_EQ(each.capture.timings.frames, 56);
  EXPECT_EQ(each.capture.cuts, 0);
  EXPECT_EQ(each.faces[0].first_frame, 8);  // the first frame with a face
  // The right face slides in over frames 20-28; the whole frame is searched
  // every 8 (half of the face shows at 24).
  const int entered = each.faces[1].first_frame;
  EXPECT_TRUE(entered == 24 || entered == 32) << entered;
  EXPECT_LT(each.faces[0].box.center().x(), 640.0f);
  EXPECT_GT(each.faces[1].box.center().x(), 640.0f);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(each.runs[k].capture.lost, 0) << k;
    EXPECT_GT(each.runs[k].capture.identity.frames_used, 0) << k;
    const auto rows = lines(face_folder(out, k) / "frames.jsonl");
    ASSERT_EQ(int(rows.size()), 56 - each.faces[k].first_frame) << k;
    EXPECT_EQ(nlohmann::json::parse(rows.front())["frame"], each.faces[k].first_frame) << k;
    for (const std::string& row : rows) {
      const nlohmann::json frame = nlohmann::json::parse(row);
      ASSERT_NE(frame["status"], "lost") << k;
      float x = 0;
      for (const auto& p : frame["landmarks"]) x += p[0].get<float>() / 68;
      EXPECT_EQ(x > 640.0f, k == 1) << "face " << k << ": " << x;
    }
  }
  // Two people, two identities.
  EXPECT_GT((each.runs[0].capture.identity.identity - each.runs[1].capture.identity.identity).norm(), 1.0);
  std::ifstream list_in(out / "faces.json");
  const nlohmann::json list = nlohmann::json::parse(list_in);
  ASSERT_EQ(list["faces"].size(), 2u);
  EXPECT_EQ(list["faces"][1]["folder"], "face_1");
  EXPECT_EQ(list["faces"][1]["found_in_frame"], entered);
  // faces.png shows who is who: each face where it was found.
  const cv::Mat sheet = facecap::read_image((out / "faces.png").string());
  ASSERT_EQ(sheet.cols, 2 * FoundFace::kThumbnailSize);
  for (int k = 0; k < 2; ++k) {
    const cv::Mat tile = sheet(cv::Rect(k * FoundFace::kThumbnailSize, 0, FoundFace::kThumbnailSize / 2,
                                        FoundFace::kThumbnailSize));  // its left half: the right face's is cut off
    EXPECT_GT(cv::mean(tile)[1], 40.0) << k;
    const cv::Rect tile_rect(k * FoundFace::kThumbnailSize, 0, FoundFace::kThumbnailSize, FoundFace::kThumbnailSize);
    EXPECT_EQ(cv::norm(sheet(tile_rect), each.faces[k].thumbnail, cv::NORM_INF), 0.0) << k;  // lossless
  }
  EXPECT_FALSE(fs::exists(out / "face_2"));
  std::map<std::string, int> datagrams;
  while (const auto d = receiver.receive(200)) ++datagrams[test::decode_livelink(*d).subject];
  EXPECT_EQ(datagrams, (std::map<std::string, int>{{"facecap_face0", 48}, {"facecap_face1", 56 - entered}}));
  for (int k = 0; k < 2; ++k) EXPECT_EQ(each.runs[k].livelink_sent, 56 - each.faces[k].first_frame) << k;
  EXPECT_TRUE(fs::exists(out / "face_notes"));

  // --max-faces 1: the second is not captured, and that is said.
  AllFacesOptions one_face;
  one_face.max_faces = 1;
  const EachFaceSummary one = run_track_each_face(*model, two.string(), dir.path() / "one", o, one_face);
  ASSERT_EQ(one.faces.size(), 1u);
  EXPECT_EQ(one.capture.uncaptured_faces, 1);
  EXPECT_EQ(one.runs[0].capture.frames, 48);

  // --max-frames counts the input's frames: each face sees those left from
  // where it was found, and so does its overlay.
  TrackOptions some = o;
  some.capture.max_frames = 40;
  some.overlay = true;
  const EachFaceSummary first40 = run_track_each_face(*model, two.string(), dir.path() / "first40", some);
  ASSERT_EQ(first40.runs.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const int frames = 40 - first40.faces[k].first_frame;
    EXPECT_EQ(first40.runs[k].capture.frames, frames) << k;
    EXPECT_EQ(open_input((face_folder(dir.path() / "first40", k) / "overlay.mp4").string())->info().frames, frames)
        << k;
  }

  // An input with no face is an error, and nothing is written.
  const fs::path grey = faceless_image(dir.path());
  EXPECT_THROW(run_track_each_face(*model, grey.string(), dir.path() / "none", o), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "none"));
}

// transform --all-faces: both people transformed in one output, each as a
// run of its own transforms them (--start where the face was found, --face
// there), frame for frame; what no face covers is the input's. The right
// face has an expression of its own (--face-to 1=sadness), the left one
// --to's.
TEST(TransformJob, AllFacesTransformsEachFaceAsItsOwnRunDoes) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(left, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(right, "talking_webcam2_400x300.mp4");
  TempDir dir;
  const fs::path two = two_people_clip(left, right, dir.path() / "two.mp4");
  const std::vector<cv::Mat> input = decoded_frames(two);
  ASSERT_EQ(input.size(), 56u);

  TransformJobOptions o;
  o.capture.quiet = true;
  o.description = "test";
  const ExpressionSchedule sadness = ExpressionSchedule::constant(Emotion::kSadness, 1.0);
  TransformJobOptions sad_right = o;
  sad_right.face_expressions[1] = {sadness, "neutral to sadness"};
  std::map<int, cv::Mat> both;
  sad_right.on_frame = [&](int index, const cv::Mat& image) {
    EXPECT_TRUE(both.empty() || index == both.rbegin()->first + 1) << index;  // in order, each once
    both[index] = image.clone();
  };
  const fs::path out = dir.path() / "both.mp4";
  sad_right.matte = dir.path() / "both_matte.mp4";
  const AllFacesTransformSummary s = run_transform_all_faces(*model, two.string(), out, sad_right);
  ASSERT_EQ(s.frames.size(), 2u);
  ASSERT_EQ(both.size(), 56u);
  EXPECT_EQ(s.timings.frames, 56);
  EXPECT_EQ(open_input(out.string())->info().frames, 56);
  std::ifstream sidecar(out.string() + ".json");
  const nlohmann::json mark = nlohmann::json::parse(sidecar);
  EXPECT_EQ(mark["parameters"]["faces"], "2");
  EXPECT_EQ(mark["parameters"]["face_1"], "neutral to sadness");
  EXPECT_NE(mark["description"].get<std::string>().find("face 1: neutral to sadness"), std::string::npos);
  const int entered = s.capture.faces[1].first_frame;
  EXPECT_TRUE(entered == 24 || entered == 32) << entered;
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(int(s.frames[k].size()), 56 - s.capture.faces[k].first_frame) << k;
    EXPECT_TRUE(std::all_of(s.frames[k].begin(), s.frames[k].end(), [](const TransformedFrame& f) { return f.valid; }))
        << k;
  }

  // --matte: each face's re-rendered share in its half, from where it was found.
  const std::vector<cv::Mat> matte = decoded_frames(sad_right.matte);
  ASSERT_EQ(matte.size(), 56u);
  for (int k = 0; k < 2; ++k) {
    const cv::Rect half(640 * k, 0, 640, 360);
    for (int i = 0; i < 56; ++i) {
      const int face = cv::countNonZero(matte[i](half).reshape(1) > 128);
      if (i < s.capture.faces[k].first_frame) {
        EXPECT_EQ(face, 0) << k << " " << i;
      } else {
        EXPECT_GT(face, 3000) << k << " " << i;
      }
    }
  }

  // Each face alone, from where it was found, with its expression.
  auto alone = [&](int k) {
    TransformJobOptions one = o;
    if (k == 1) one.transform.schedule = sadness;
    std::map<int, cv::Mat> frames;
    one.on_frame = [&](int index, const cv::Mat& image) { frames[index] = image.clone(); };
    one.capture.start_seconds = s.capture.faces[k].first_time;
    one.capture.tracker.pick = {FacePick::Rule::kNearest, s.capture.faces[k].box.center()};
    const TransformSummary r =
        run_transform(*model, two.string(), dir.path() / ("face" + std::to_string(k) + ".mp4"), one);
    EXPECT_EQ(r.frames.size(), s.frames[k].size()) << k;
    return frames;
  };
  expect_each_half_as_its_own_run(both, alone(0), alone(1), input, entered);

  // A glTF or a plot is one face's: asked for with every face, it is an
  // error before any work.
  TransformJobOptions with_plot = o;
  with_plot.plot = dir.path() / "plot.png";
  EXPECT_THROW(run_transform_all_faces(*model, two.string(), dir.path() / "plot.mp4", with_plot), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "plot.mp4"));
  // A face both left as it is and given an expression, or an expression per
  // face without every face: errors before any work.
  AllFacesOptions leave_right;
  leave_right.unedited = {1};
  EXPECT_THROW(run_transform_all_faces(*model, two.string(), dir.path() / "left.mp4", sad_right, leave_right), Error);
  EXPECT_THROW(run_transform(*model, two.string(), dir.path() / "left.mp4", sad_right), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "left.mp4"));
  // No face anywhere: an error, and nothing is written.
  const fs::path grey = faceless_image(dir.path());
  o.on_frame = nullptr;
  EXPECT_THROW(run_transform_all_faces(*model, grey.string(), dir.path() / "none.png", o), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "none.png"));
}

// swap --all-faces: the source's face on both people in one output, each as
// a run of its own puts it there (--start where the face was found, --face
// there), frame for frame; what no face covers is the input's. The right
// face gets a source of its own (--face-source 1=PHOTO).
TEST(SwapJob, AllFacesSwapsEachFaceAsItsOwnRunDoes) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(left, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(right, "talking_webcam2_400x300.mp4");
  FACECAP_REQUIRE_DATA(photo, "portrait_biden.jpg");
  FACECAP_REQUIRE_DATA(other, "portrait_obama.jpg");
  TempDir dir;
  const fs::path two = two_people_clip(left, right, dir.path() / "two.mp4");
  const std::vector<cv::Mat> input = decoded_frames(two);
  SwapJobOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = 40;  // the right face from 24 or 32 on
  SwapJobOptions own_right = o;
  own_right.face_sources[1] = other.string();
  std::map<int, cv::Mat> both;
  own_right.on_output_frame = [&](int index, const cv::Mat& image) {
    EXPECT_TRUE(both.empty() || index == both.rbegin()->first + 1) << index;  // in order, each once
    both[index] = image.clone();
  };
  const fs::path out = dir.path() / "both.mp4";
  own_right.matte = dir.path() / "both_matte.mp4";
  const AllFacesSwapSummary s = run_swap_all_faces(*model, photo.string(), two.string(), out, own_right);
  ASSERT_EQ(s.swapped.size(), 2u);
  ASSERT_EQ(both.size(), 40u);
  EXPECT_EQ(open_input(out.string())->info().frames, 40);
  std::ifstream sidecar(out.string() + ".json");
  const nlohmann::json mark = nlohmann::json::parse(sidecar);
  EXPECT_EQ(mark["parameters"]["faces"], "2");
  EXPECT_EQ(mark["parameters"]["face_1_source"], other.string());
  EXPECT_EQ(mark["sources"], (std::vector<std::string>{photo.string(), two.string(), other.string()}));
  EXPECT_EQ(mark["edit"], "face-swap");
  ASSERT_EQ(s.face_sources.size(), 1u);
  EXPECT_GT((s.face_sources.at(1).face.identity - s.source.face.identity).norm(), 1.0);  // two people
  const int entered = s.target.faces[1].first_frame;
  ASSERT_TRUE(entered == 24 || entered == 32) << entered;
  for (int k = 0; k < 2; ++k) EXPECT_EQ(s.swapped[k], 40 - s.target.faces[k].first_frame) << k;

  auto alone = [&](int k) {
    SwapJobOptions one = o;
    std::map<int, cv::Mat> frames;
    one.on_output_frame = [&](int index, const cv::Mat& image) { frames[index] = image.clone(); };
    one.capture.start_seconds = s.target.faces[k].first_time;
    one.capture.max_frames = 40 - s.target.faces[k].first_frame;
    one.capture.tracker.pick = {FacePick::Rule::kNearest, s.target.faces[k].box.center()};
    one.matte = dir.path() / ("face" + std::to_string(k) + "_matte.mp4");
    run_swap(*model, (k == 1 ? other : photo).string(), two.string(),
             dir.path() / ("face" + std::to_string(k) + ".mp4"), one);
    return frames;
  };
  expect_each_half_as_its_own_run(both, alone(0), alone(1), input, entered);
  // --matte: each half of the matte is its face's own run's matte (within
  // the grey levels' rounding), and nothing before that face is found.
  EXPECT_TRUE(carries_synthetic_marks(own_right.matte));
  const std::vector<cv::Mat> matte = decoded_frames(own_right.matte);
  ASSERT_EQ(matte.size(), 40u);
  const cv::Rect halves[2] = {cv::Rect(0, 0, 640, 360), cv::Rect(640, 0, 640, 360)};
  for (int k = 0; k < 2; ++k) {
    const int first = s.target.faces[k].first_frame;
    const std::vector<cv::Mat> own = decoded_frames(dir.path() / ("face" + std::to_string(k) + "_matte.mp4"));
    ASSERT_EQ(int(own.size()), 40 - first) << k;
    for (int i = 0; i < 40; ++i) {
      const cv::Mat half = matte[i](halves[k]);
      if (i < first) {
        EXPECT_EQ(cv::norm(half, cv::NORM_INF), 0.0) << k << " " << i;
        continue;
      }
      EXPECT_LE(cv::norm(half, own[i - first](halves[k]), cv::NORM_INF), 3.0) << k << " " << i;
      EXPECT_GT(cv::countNonZero(half.reshape(1) > 128), 3000) << k << " " << i;  // the face
    }
  }
  // --leave-faces 0: the left face is followed and left as it is; the right
  // one is swapped as before.
  std::map<int, cv::Mat> spared;
  SwapJobOptions leave = own_right;
  leave.on_output_frame = [&](int index, const cv::Mat& image) { spared[index] = image.clone(); };
  AllFacesOptions leave_first;
  leave_first.unedited = {0};
  const AllFacesSwapSummary l =
      run_swap_all_faces(*model, photo.string(), two.string(), dir.path() / "spared.mp4", leave, leave_first);
  EXPECT_EQ(l.swapped, (std::vector<int>{0, 40 - entered}));
  ASSERT_EQ(spared.size(), 40u);
  const cv::Rect left_half(0, 0, 640, 360), right_half(640, 0, 640, 360);
  for (const auto& [i, frame] : spared) {
    EXPECT_EQ(cv::norm(frame(left_half), input[i](left_half), cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(frame(right_half), both.at(i)(right_half), cv::NORM_INF), 0.0) << i;
  }
  std::ifstream spared_mark((dir.path() / "spared.mp4").string() + ".json");
  EXPECT_EQ(nlohmann::json::parse(spared_mark)["parameters"]["faces"], "1");
  // A face both left as it is and given a source, or a source per face
  // without every face: errors before any work.
  leave_first.unedited = {0, 1};
  EXPECT_THROW(run_swap_all_faces(*model, photo.string(), two.string(), dir.path() / "none.mp4", leave, leave_first),
               Error);
  EXPECT_THROW(run_swap(*model, photo.string(), two.string(), dir.path() / "none.mp4", leave), Error);
  // Every face left as it is: nothing to swap, said so, and nothing written.
  leave.face_sources.clear();
  try {
    run_swap_all_faces(*model, photo.string(), two.string(), dir.path() / "none.mp4", leave, leave_first);
    ADD_FAILURE() << "every face left, yet a swap";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--leave-faces"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.path() / "none.mp4"));

  // A glTF is one face's: asked for with every face, an error before any work.
  SwapJobOptions with_gltf = o;
  with_gltf.gltf = dir.path() / "swap.glb";
  EXPECT_THROW(run_swap_all_faces(*model, photo.string(), two.string(), dir.path() / "gltf.mp4", with_gltf), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "gltf.mp4"));
  // No face in the target: an error, and nothing is written.
  const fs::path grey = faceless_image(dir.path());
  EXPECT_THROW(run_swap_all_faces(*model, photo.string(), grey.string(), dir.path() / "none.png", o), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "none.png"));
}

// --all-faces: a face covered for 8 frames comes back into its own folder
// (no third one); after a cut to a shot with one face on the right, that face
// goes to the capture that began on the right, with an identity of its own.
TEST(TrackJob, AllFacesKeepsEachFaceInItsFolderThroughCoverAndCuts) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(left, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(right, "talking_webcam2_400x300.mp4");
  FACECAP_REQUIRE_DATA(later, "address_720p_b.mp4");
  TempDir dir;
  const fs::path video = compose_clip(
      {left, right, later},
      "[0:v]trim=end_frame=48,scale=640:360,setsar=1,drawbox=x=0:y=0:w=640:h=360:color=black:t=fill:enable='between(n,"
      "24,31)'[l];[1:v]trim=end_frame=48,scale=480:360,pad=640:360:80:0,setsar=1[r];[l][r]hstack[A];[2:v]trim=end_"
      "frame=24,scale=640:360,pad=1280:360:640:0,setsar=1[B];[A][B]concat=n=2:v=1[v]",
      dir.path() / "cut.mp4");
  TrackOptions o;
  o.capture.quiet = true;
  const EachFaceSummary each = run_track_each_face(*model, video.string(), dir.path() / "out", o);
  ASSERT_EQ(each.faces.size(), 2u);
  EXPECT_EQ(each.capture.cuts, 1);
  for (int k = 0; k < 2; ++k) EXPECT_EQ(each.faces[k].first_frame, 0) << k;
  const auto rows = [&](int k) {
    std::vector<nlohmann::json> out;
    for (const std::string& line : lines(face_folder(dir.path() / "out", k) / "frames.jsonl"))
      out.push_back(nlohmann::json::parse(line));
    return out;
  };
  const std::vector<nlohmann::json> left_rows = rows(0), right_rows = rows(1);
  ASSERT_EQ(left_rows.size(), 72u);
  ASSERT_EQ(right_rows.size(), 72u);
  for (int f = 0; f < 72; ++f) {
    // The left face: lost while covered and after the cut, and only then.
    const bool covered = f >= 24 && f < 32;
    EXPECT_EQ(left_rows[f]["status"] == "lost", covered || f >= 48) << f;
    // The right face: every frame, on the right, in both shots.
    ASSERT_NE(right_rows[f]["status"], "lost") << f;
    float x = 0;
    for (const auto& p : right_rows[f]["landmarks"]) x += p[0].get<float>() / 68;
    EXPECT_GT(x, 640.0f) << f;
    EXPECT_EQ(right_rows[f]["shot"], f < 48 ? 0 : 1) << f;
  }
  // The right capture's two shots are two people.
  const std::vector<CaptureSummary::Shot>& shots = each.runs[1].capture.shots;
  ASSERT_EQ(shots.size(), 2u);
  EXPECT_EQ(shots[1].first_frame, 48);
  EXPECT_GT((shots[0].identity.identity - shots[1].identity.identity).norm(), 1.0);
}

}  // namespace facecap
